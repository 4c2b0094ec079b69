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

// The interpolation error allowed at a gathered leaf, as a share of the solution's tolerance (e × what
// it shows): a quarter, since a shadow's edge is what the eye finds first. On the Cornell box (default
// error, every source by the contour formula, a budget of half the leaves) 1, 0.5, 0.25 and 0.1 gave
// 0.96, 0.96, 0.92 and 0.91% weighted RMS.
constexpr double kInterpolationShare = 0.25;

uint64_t point_seed(const Vec3& x) {
  uint64_t bits[3];
  std::memcpy(&bits[0], &x.x, 8);
  std::memcpy(&bits[1], &x.y, 8);
  std::memcpy(&bits[2], &x.z, 8);
  return Rng(bits[0] ^ (bits[1] * 0x9E3779B97F4A7C15ull), bits[2]).next();
}

}  // namespace

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
      seen += blocked[size_t(k)] ? 0.0 : kernel[size_t(k)];
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

namespace {

// How far leaf's ρD departs from its Gouraud interpolation (luminance): the largest difference at an
// edge's quarter, half and three-quarter points and at the centre (a quad's centre lies on the
// diagonal v0–v2 its two triangles share). The quarters catch a penumbra that a leaf straddles
// symmetrically: at its midpoint the light is half on, as the corners' mean says.
double interpolation_error(const Hierarchy& h, const DirectGather& g, uint32_t leaf, const Vec3& tau, uint64_t& rays) {
  const HNode& n = h[leaf];
  const EmitterRanges from = g.candidates(leaf);
  const Vec3 c = polygon_centroid(n.shape);
  auto shade = [&](const Vec3& x) {
    Vec3 inward = c - x;
    const double len = length(inward);
    inward = len > 0 ? inward / len : Vec3{};
    Vec3 shown = mul(n.rho, g.at(x, n.normal, inward, from, rays, DirectGather::kTestPenumbra));
    // A transmitting leaf shows τ times its back's light too: the punctual lights' (the mesher's
    // LeafRadiosity takes their variation at the point; lamp-room's bulb inside its shade).
    if (max_component(tau) > 0) shown += mul(tau, g.at(x, n.normal * -1.0, inward, {}, rays, DirectGather::kTestPenumbra));
    return luminance(shown);
  };
  std::array<double, 4> corner{};
  for (int k = 0; k < n.shape.count; ++k) corner[size_t(k)] = shade(n.shape.v[size_t(k)]);
  double worst = 0;
  for (int k = 0; k < n.shape.count; ++k) {
    const int m = (k + 1) % n.shape.count;
    for (const double t : {0.25, 0.5, 0.75}) {
      const double along = shade(n.shape.v[size_t(k)] * (1 - t) + n.shape.v[size_t(m)] * t);
      worst = std::max(worst, std::fabs(along - ((1 - t) * corner[size_t(k)] + t * corner[size_t(m)])));
    }
  }
  const double interpolated = n.shape.count == 4 ? 0.5 * (corner[0] + corner[2]) : (corner[0] + corner[1] + corner[2]) / 3.0;
  return std::max(worst, std::fabs(shade(c) - interpolated));
}

}  // namespace

uint64_t refine_for_gather(Hierarchy& h, const DirectGather& g, const GatherRefinement& r, uint64_t& rays_cast) {
  if ((g.emitter_count() == 0 && !g.has_lights()) || r.white <= 0) return 0;
  auto twin_of = [&](const HNode& n) { return r.twins ? (*r.twins)[n.polygon] : kNoTwin; };
  auto tau_of = [&](const HNode& n) {
    return twin_of(n) == kNoTwin ? Vec3{} : material_transmittance(h, n);
  };
  std::vector<uint32_t> batch;
  for (uint32_t i = 0; i < h.nodes().size(); ++i) {
    const HNode& n = h[i];
    if (!is_leaf_element(n) || max_component(n.emission) > 0) continue;
    if (r.seen && !(*r.seen)[n.polygon]) continue;
    if (twin_of(n) != kNoTwin && !g.has_lights()) continue;  // its back's light is the links' alone
    batch.push_back(i);
  }
  // The leaves over their tolerance wait in one queue, the worst first whatever its depth: level by
  // level, a budget spent on the first level's many slight excesses left a 5 cm penumbra, whose
  // excess is larger, unsplit below it. Splits are taken kBatch at a time, their children tested in
  // parallel; ties go to the lower node index, so the result depends on no thread count.
  constexpr size_t kBatch = 256;
  using Entry = std::pair<double, uint32_t>;  // excess, node
  auto worse = [](const Entry& a, const Entry& b) { return a.first < b.first || (a.first == b.first && a.second > b.second); };
  std::vector<Entry> queue;  // a heap under `worse`
  uint64_t splits = 0;
  std::atomic<uint64_t> rays{0};
  while (!batch.empty()) {
    // Each leaf tested on the rank holding its links (the candidates are its ancestors'), and its
    // excess given to every rank (link_owners.h): the queue and the splits are the same on all.
    std::vector<double> excess(batch.size(), 0.0);
    auto rank_of = [&](size_t k) { return polygon_rank(h, h[batch[k]].polygon); };
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batch.size(), 16), [&](const tbb::blocked_range<size_t>& range) {
      uint64_t cast = 0;
      for (size_t k = range.begin(); k != range.end(); ++k) {
        if (!h.owners().holds_polygon(h[batch[k]].polygon)) continue;
        const HNode& n = h[batch[k]];
        if (n.depth >= r.max_depth || n.area * 0.25 < r.min_area) continue;
        const double shown = std::clamp(luminance(n.B), 0.1 * r.white, r.white);
        excess[k] = interpolation_error(h, g, batch[k], tau_of(n), cast) / (kInterpolationShare * r.error * shown);
      }
      rays += cast;
    });
    if (h.owners().divided()) share_owned(excess, rank_of);
    for (size_t k = 0; k < batch.size(); ++k)
      if (excess[k] > 1) {
        queue.push_back({excess[k], batch[k]});
        std::push_heap(queue.begin(), queue.end(), worse);
      }
    batch.clear();
    while (!queue.empty() && batch.size() < 4 * kBatch && splits * 4 < r.budget) {
      std::pop_heap(queue.begin(), queue.end(), worse);
      const uint32_t i = queue.back().second;
      queue.pop_back();
      h.subdivide(i);
      ++splits;
      const uint32_t twin = twin_of(h[i]);
      const Vec3 tau = tau_of(h[i]), twin_D = twin == kNoTwin ? Vec3{} : twin_direct(h, h[i], twin);
      for (uint32_t c = 0; c < 4; ++c) {
        const uint32_t child = h.child(h[i], c);
        HNode& kid = h[child];
        const HNode& parent = h[i];
        kid.receive = parent.receive;
        kid.send = parent.send;
        kid.balanced = parent.balanced;
        kid.D = parent.D;
        kid.D_known = parent.D_known;
        kid.Hl = parent.Hl;
        // A transmitting kid passes on its twin's light at its own place (twin_direct, as the mesher
        // takes it there): B as the solve would have made it from the twin's D.
        if (twin != kNoTwin) {
          const Vec3 change = mul(tau, twin_direct(h, kid, twin) - twin_D);
          kid.B += change;
          kid.Bt += change * kid.send;
        }
        batch.push_back(child);
      }
    }
  }
  int64_t all_rays = int64_t(rays.load());
  if (h.owners().divided()) all_sum(&all_rays, 1);
  rays_cast += uint64_t(all_rays);
  return splits;
}

}  // namespace walkrad
