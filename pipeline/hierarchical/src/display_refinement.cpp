#include "walkrad/hierarchical/display_refinement.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <functional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/formfactor/form_factor.h"
#include "walkrad/hierarchical/link_owners.h"
#include "walkrad/hierarchical/link_transport.h"
#include "walkrad/hierarchical/point_radiosity.h"
#include "walkrad/hierarchical/transmission.h"
#include "walkrad/scene/transmission_twins.h"

namespace walkrad {

namespace {

// How far a leaf's shown light (luminance, from shade) departs from its Gouraud interpolation: the
// largest difference at an edge's quarter, half and three-quarter points and at the centre (a quad's
// centre lies on the diagonal v0–v2 its two triangles share). The quarters catch a penumbra that a leaf
// straddles symmetrically: at its midpoint the light is half on, as the corners' mean says.
double interpolation_error(const HNode& n, const std::function<double(const Vec3&)>& shade) {
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
  return std::max(worst, std::fabs(shade(polygon_centroid(n.shape)) - interpolated));
}

// A gathered leaf: ρD as the final gather evaluates it, with shadow rays, from the emitters that can
// move it: those whose light together stays below a quarter of the departure allowed (`allowed`) can
// add at most twice that to the departure found (an interpolation of values in [0, b] departs from
// them by at most b), and are left out of the test.
double gathered_error(const Hierarchy& h, const DirectGather& g, uint32_t leaf, const Vec3& tau, double allowed,
                      uint64_t& rays) {
  const HNode& n = h[leaf];
  const Vec3 c = polygon_centroid(n.shape);
  std::array<Vec3, 5> points{c};
  for (int k = 0; k < n.shape.count; ++k) points[size_t(k + 1)] = n.shape.v[size_t(k)];
  const EmitterRanges from = g.strongest(g.candidates(leaf), points.data(), size_t(n.shape.count + 1), n.normal, n.rho,
                                         0.25 * allowed);
  return interpolation_error(n, [&](const Vec3& x) {
    Vec3 inward = c - x;
    const double len = length(inward);
    inward = len > 0 ? inward / len : Vec3{};
    Vec3 shown = mul(n.rho, g.at(x, n.normal, inward, from, rays, DirectGather::kTestPenumbra));
    // A transmitting leaf shows τ times its back's light too: the punctual lights' (the mesher's
    // LeafRadiosity takes their variation at the point; lamp-room's bulb inside its shade).
    if (max_component(tau) > 0) shown += mul(tau, g.at(x, n.normal * -1.0, inward, {}, rays, DirectGather::kTestPenumbra));
    return luminance(shown);
  });
}

// Another leaf: the light of the emitting sources its vertices take at the point (taken_at_points),
// each by the fraction of it its link sees. 0 where it has none (nothing to interpolate but shares).
double ungathered_error(const Hierarchy& h, const std::vector<Vec3>& emitted, uint32_t leaf) {
  const HNode& n = h[leaf];
  struct Source {
    const Polygon* shape;
    Vec3 normal, sent;
  };
  std::vector<Source> sources;
  for (int32_t a = int32_t(leaf); a >= 0 && !h[uint32_t(a)].cluster; a = h[uint32_t(a)].parent) {
    const HNode& r = h[uint32_t(a)];
    for (const Link& l : r.links) {
      const HNode& s = h[l.source];
      if (!carries(l) || s.cluster || max_component(emitted[l.source]) <= 0 || !taken_at_points(h, r, l)) continue;
      sources.push_back({&s.shape, s.normal, emitted[l.source] * (double(l.F) / double(l.open))});
    }
  }
  if (sources.empty()) return 0.0;
  return interpolation_error(n, [&](const Vec3& x) {
    Vec3 E;
    for (const Source& s : sources)
      if (dot(x - s.shape->v[0], s.normal) > 0) E += s.sent * point_to_polygon(x, n.normal, *s.shape);
    return luminance(mul(n.rho, E));
  });
}

}  // namespace

uint64_t refine_display(Hierarchy& h, const DirectGather* g, const DisplayRefinement& r, uint64_t& rays_cast) {
  const bool gathering = g && (g->emitter_count() > 0 || g->has_lights());
  if ((!gathering && !r.ungathered) || r.white <= 0) return 0;
  auto twin_of = [&](const HNode& n) { return r.twins ? (*r.twins)[n.polygon] : kNoTwin; };
  auto tau_of = [&](const HNode& n) {
    return twin_of(n) == kNoTwin ? Vec3{} : material_transmittance(h, n);
  };
  const double reach = view_reach(h);
  auto gathered = [&](const HNode& n) {
    return gathering && (!r.seen || (*r.seen)[n.polygon]) && in_view(h, uint32_t(&n - h.nodes().data()), reach);
  };
  const std::vector<Vec3> emitted = r.ungathered ? emitted_as_sent(h) : std::vector<Vec3>{};
  std::vector<uint32_t> batch;
  for (uint32_t i = 0; i < h.nodes().size(); ++i) {
    const HNode& n = h[i];
    if (!is_leaf_element(n) || max_component(n.emission) > 0) continue;
    if (twin_of(n) != kNoTwin && !(gathered(n) && g->has_lights())) continue;  // its back's light is the links' alone
    if (!gathered(n) && !r.ungathered) continue;
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
  // Each tested leaf's departure (luminance), for the bake's estimate: the leaves that stay leaves add
  // it to their error (HNode::error) as an RMS over the leaf, half the largest departure (a bump's
  // Gouraud error is largest at its peak and 0 at the corners).
  std::vector<std::pair<uint32_t, float>> departure;
  uint64_t splits = 0;
  std::atomic<uint64_t> rays{0};
  while (!batch.empty()) {
    // Each leaf tested on the rank holding its links (the candidates are its ancestors'), and its
    // excess given to every rank (link_owners.h): the queue and the splits are the same on all.
    std::vector<double> found(batch.size(), 0.0), excess(batch.size(), 0.0);
    auto rank_of = [&](size_t k) { return polygon_rank(h, h[batch[k]].polygon); };
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batch.size(), 16), [&](const tbb::blocked_range<size_t>& range) {
      uint64_t cast = 0;
      for (size_t k = range.begin(); k != range.end(); ++k) {
        if (!h.owners().holds_polygon(h[batch[k]].polygon)) continue;
        const HNode& n = h[batch[k]];
        if (n.depth >= r.max_depth || n.area * 0.25 < r.min_area) continue;
        if (!gathered(n) && !r.ungathered) continue;  // a split leaf's child out of view
        const double shown = std::clamp(luminance(n.B), 0.1 * r.white, r.white);
        const double allowed = kInterpolationShare * r.error * shown;
        found[k] = gathered(n) ? gathered_error(h, *g, batch[k], tau_of(n), allowed, cast) : ungathered_error(h, emitted, batch[k]);
        excess[k] = found[k] / allowed;
      }
      rays += cast;
    });
    if (h.owners().divided()) share_owned(excess, rank_of), share_owned(found, rank_of);
    for (size_t k = 0; k < batch.size(); ++k)
      if (found[k] > 0) departure.push_back({batch[k], float(found[k])});
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
  for (const auto& [leaf, d] : departure) {
    HNode& n = h[leaf];
    if (n.child_count == 0) n.error = std::sqrt(n.error * n.error + 0.25f * d * d);
  }
  int64_t all_rays = int64_t(rays.load());
  if (h.owners().divided()) all_sum(&all_rays, 1);
  rays_cast += uint64_t(all_rays);
  return splits;
}

}  // namespace walkrad
