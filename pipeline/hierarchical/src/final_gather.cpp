#include "walkrad/hierarchical/final_gather.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <iterator>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/core/sampling.h"
#include "walkrad/formfactor/form_factor.h"
#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/hierarchical/link_owners.h"
#include "walkrad/hierarchical/link_transport.h"
#include "walkrad/hierarchical/transmission.h"
#include "walkrad/scene/transmission_twins.h"

namespace walkrad {

namespace {

// Stratified points over the emitter: a first pass, and a finer one where the first disagrees (at most
// kFinest a side). In a 5 cm penumbra (test ContactShadow) 8 and 16 a side left 3.1 and 2.7% RMS, 32
// at the vertices 2.4%: a shadow edge crosses about m of the m² strata, each a coin toss.
constexpr int kFirst = 4, kFinest = DirectGather::kVertexPenumbra;
constexpr double kCornerInset = 0.01;  // of the way to the emitter's centre

uint64_t point_seed(const Vec3& x) {
  uint64_t bits[3];
  std::memcpy(&bits[0], &x.x, 8);
  std::memcpy(&bits[1], &x.y, 8);
  std::memcpy(&bits[2], &x.z, 8);
  return Rng(bits[0] ^ (bits[1] * 0x9E3779B97F4A7C15ull), bits[2]).next();
}

}  // namespace

bool in_view(const Hierarchy& h, uint32_t leaf, double reach) {
  if (h.hits().empty()) return true;
  int32_t a = int32_t(leaf);
  while (!h[uint32_t(a)].cluster && h[uint32_t(a)].depth > 0 && h[uint32_t(a)].area < reach) a = h[uint32_t(a)].parent;
  return h[uint32_t(a)].hit_end > h[uint32_t(a)].hit_begin;
}

double view_reach(const Hierarchy& h) { return default_min_area(h) * 128.0 * 128.0; }

void merge_ranges(EmitterRanges& a, const EmitterRanges& b) {
  if (b.empty()) return;
  EmitterRanges all;
  all.reserve(a.size() + b.size());
  std::merge(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(all));
  a.clear();
  for (const auto& r : all) {
    if (!a.empty() && r.first <= a.back().second) a.back().second = std::max(a.back().second, r.second);
    else a.push_back(r);
  }
}

DirectGather::DirectGather(const Hierarchy& h, const std::vector<PunctualLight>* lights, const RayScene* rays)
    : h_(h), lights_(lights && !lights->empty() ? lights : nullptr), rays_(rays),
      polygon_emitter_(h.scene().polygons.size(), UINT32_MAX) {
  const ClusterTree& tree = h.tree();
  for (uint32_t k = 0; k < tree.polygons.size(); ++k) {
    const uint32_t p = tree.polygons[k];
    const HNode& root = h[h.polygon_root(p)];
    if (max_component(root.emission) <= 0) continue;
    polygon_emitter_[p] = uint32_t(emitters_.size());
    Emitter e{root.shape, root.normal, root.emission, p, {}};
    const Vec3 centre = polygon_centroid(e.shape);
    for (int c = 0; c < e.shape.count; ++c) e.inset[size_t(c)] = e.shape.v[c] + (centre - e.shape.v[c]) * kCornerInset;
    emitters_.push_back(e);
    emitter_position_.push_back(k);
  }
  // Each cluster's emitters from its own links, merged with its parent's (parents come first).
  cluster_ranges_.resize(h.nodes().size());
  if (emitters_.empty()) return;
  for (uint32_t i = 0; i < h.nodes().size(); ++i) {
    const HNode& n = h[i];
    if (!n.cluster) continue;
    if (n.parent >= 0) cluster_ranges_[i] = cluster_ranges_[size_t(n.parent)];
    for (const Link& l : n.links)
      if (l.F > 0) merge_ranges(cluster_ranges_[i], ranges_of(h[l.source]));
  }
}

EmitterRanges DirectGather::ranges_of(const HNode& s) const {
  if (!s.cluster) {
    const uint32_t e = polygon_emitter_[s.polygon];
    return e == UINT32_MAX ? EmitterRanges{} : EmitterRanges{{e, e + 1}};
  }
  const ClusterNode& c = h_.tree().nodes[s.tree_node];
  const auto lo = std::lower_bound(emitter_position_.begin(), emitter_position_.end(), c.first);
  const auto hi = std::lower_bound(lo, emitter_position_.end(), c.first + c.count);
  if (lo == hi) return {};
  return {{uint32_t(lo - emitter_position_.begin()), uint32_t(hi - emitter_position_.begin())}};
}

EmitterRanges DirectGather::candidates(uint32_t leaf) const {
  EmitterRanges out;
  if (emitters_.empty()) return out;
  int32_t a = int32_t(leaf);
  for (; a >= 0 && !h_[uint32_t(a)].cluster; a = h_[uint32_t(a)].parent)
    for (const Link& l : h_[uint32_t(a)].links)
      if (l.F > 0) merge_ranges(out, ranges_of(h_[l.source]));
  if (a >= 0) merge_ranges(out, cluster_ranges_[size_t(a)]);
  return out;
}

std::vector<std::pair<double, uint32_t>> DirectGather::bounds(const EmitterRanges& from, const Vec3* points, size_t count,
                                                              const Vec3& n, const Vec3& rho) const {
  std::vector<std::pair<double, uint32_t>> out;
  for (const auto& [lo, hi] : from)
    for (uint32_t k = lo; k < hi; ++k) {
      const Emitter& e = emitters_[k];
      double most = 0;
      for (size_t i = 0; i < count; ++i)
        if (dot(points[i] - e.shape.v[0], e.normal) > 0) most = std::max(most, point_to_polygon(points[i], n, e.shape));
      out.push_back({luminance(mul(rho, e.emission)) * most, k});
    }
  std::sort(out.begin(), out.end());
  return out;
}

EmitterRanges without_faintest(const std::vector<std::pair<double, uint32_t>>& bounds, double negligible) {
  size_t first = 0;
  for (double sum = 0; first < bounds.size() && sum + bounds[first].first <= negligible; ++first) sum += bounds[first].first;
  std::vector<uint32_t> kept;
  for (size_t i = first; i < bounds.size(); ++i) kept.push_back(bounds[i].second);
  std::sort(kept.begin(), kept.end());
  EmitterRanges out;
  for (uint32_t k : kept) {
    if (!out.empty() && out.back().second == k) ++out.back().second;
    else out.push_back({k, k + 1});
  }
  return out;
}

EmitterRanges DirectGather::strongest(const EmitterRanges& from, const Vec3* points, size_t count, const Vec3& n,
                                      const Vec3& rho, double negligible) const {
  return without_faintest(bounds(from, points, count, n, rho), negligible);
}

double DirectGather::visible_fraction(const Vec3& x, const Vec3& n, const Vec3& from, const Emitter& e, int penumbra,
                                      uint64_t& rays_cast) const {
  const double off = rays_->offset();
  Rng rng(point_seed(x), e.polygon);
  double seen = 0, total = 0;
  int arrived = 0, cast = 0;  // rays that arrive, rays cast
  // Per thread, made once: an array of segments here zeroed its 49 KB at every call (Vec3 zeroes itself).
  thread_local std::vector<RayScene::Segment> segments(kFinest * kFinest + std::tuple_size_v<decltype(Emitter::inset)>);
  std::array<double, kFinest * kFinest> kernel;
  std::array<uint8_t, kFinest * kFinest + std::tuple_size_v<decltype(Emitter::inset)>> blocked;
  for (const int m : {kFirst, std::clamp(penumbra, kFirst, kFinest)}) {
    int count = 0;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) {
        const double v = (j + rng.uniform()) / m, u = (i + rng.uniform()) / m;  // named: argument order is unspecified (GCC's kept)
        const Vec3 y = sample_polygon(e.shape, u, v);
        const Vec3 d = y - x;
        const double r2 = dot(d, d);
        const double k = r2 > 0 ? std::max(0.0, dot(d, n)) * std::max(0.0, -dot(d, e.normal)) / (r2 * r2) : 0.0;
        kernel[size_t(count)] = k;
        segments[size_t(count++)] = {from, y + e.normal * off};
      }
    // The first pass asks the emitter's corners too (kCornerInset in from each), counted only in
    // whether the pass agrees: a point a few millimetres into a penumbra sees a strip along one edge
    // of the emitter, which 4 × 4 jittered points all missed a third of the time (test ContactShadow:
    // such points came out as umbra, −11%, once the discontinuity cuts put vertices there).
    const int corners = m == kFirst && penumbra == kFinest ? e.shape.count : 0;
    for (int c = 0; c < corners; ++c) segments[size_t(count + c)] = {from, e.inset[size_t(c)] + e.normal * off};
    rays_->occluded(segments.data(), size_t(count + corners), blocked.data());
    rays_cast += uint64_t(count + corners);
    for (int k = 0; k < count; ++k) {
      // Through clear glass, the panes' transmittance by luminance (the emitter's light is one colour here).
      const double glass = blocked[size_t(k)] || !rays_->has_glass()
                               ? 1.0
                               : luminance(rays_->transmittance(segments[size_t(k)].from, segments[size_t(k)].to));
      seen += blocked[size_t(k)] ? 0.0 : kernel[size_t(k)] * glass;
      total += kernel[size_t(k)];
      arrived += !blocked[size_t(k)];
    }
    cast += count;
    int corners_arrived = 0;
    for (int c = 0; c < corners; ++c) corners_arrived += !blocked[size_t(count + c)];
    // Wholly lit or wholly hidden, the corners agreeing: no penumbra here.
    if (m == kFirst && ((arrived == 0 && corners_arrived == 0) || (arrived == count && corners_arrived == corners))) break;
  }
  return total > 0 ? seen / total : double(arrived) / cast;
}

Vec3 DirectGather::at(const Vec3& x, const Vec3& n, const Vec3& inward, const EmitterRanges& from, uint64_t& rays_cast,
                      int penumbra) const {
  Vec3 D;
  const Vec3 origin = rays_ ? x + (n + inward) * rays_->offset() : x;
  for (const auto& [lo, hi] : from)
    for (uint32_t k = lo; k < hi; ++k) {
      const Emitter& e = emitters_[k];
      if (dot(x - e.shape.v[0], e.normal) <= 0) continue;  // behind it (or on its plane)
      const double F = point_to_polygon(x, n, e.shape);
      if (F <= 0) continue;
      D += e.emission * (F * (rays_ ? visible_fraction(x, n, origin, e, penumbra, rays_cast) : 1.0));
    }
  // From the same origin as the emitters' rays: at a vertex on a wall's foot, x + n·offset lies on the
  // wall's plane, where the shadow ray met the wall (lamp-room's floor beside the wall under its spot,
  // 1 cm out: 39% dark).
  if (lights_) D += point_irradiance(x, n, *lights_, rays_, rays_cast, &origin);
  return D;
}

}  // namespace walkrad
