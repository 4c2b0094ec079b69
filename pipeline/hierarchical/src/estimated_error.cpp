#include "walkrad/hierarchical/estimated_error.h"

#include <algorithm>
#include <cmath>

#include "walkrad/hierarchical/link_transport.h"

namespace walkrad {

EstimatedError estimate_error(const Hierarchy& h, const std::vector<ViewHit>& hits, size_t view_count) {
  std::vector<double> chain(h.nodes().size(), 0.0);  // Σ error² from the root down
  for (uint32_t i = 0; i < h.nodes().size(); ++i) {  // parents come before their children
    const double own = double(h[i].error) * double(h[i].error);
    chain[i] = own + (h[i].parent >= 0 ? chain[uint32_t(h[i].parent)] : 0.0);
  }
  auto ratio = [](double err, double ref) { return ref > 0 ? std::sqrt(err / ref) : 0.0; };
  EstimatedError out;
  if (hits.empty() || view_count == 0) {
    double err = 0, ref = 0;
    for (uint32_t i = 0; i < h.nodes().size(); ++i)
      if (is_leaf_element(h[i]) && max_component(h[i].emission) == 0) {
        err += h[i].area * chain[i];
        ref += h[i].area * luminance(h[i].B) * luminance(h[i].B);
      }
    out.overall = ratio(err, ref);
    return out;
  }
  const size_t segments = std::min(kEstimateSegments, view_count);
  std::vector<double> err(segments, 0.0), ref(segments, 0.0);
  for (const ViewHit& hit : hits) {
    const uint32_t leaf = leaf_at(h, h.polygon_root(hit.polygon), hit.point);
    if (max_component(h[leaf].emission) > 0) continue;
    const size_t k = std::min(segments - 1, size_t(hit.view) * segments / view_count);
    err[k] += hit.weight * chain[leaf];
    ref[k] += hit.weight * luminance(h[leaf].B) * luminance(h[leaf].B);
  }
  double e = 0, r = 0;
  for (size_t k = 0; k < segments; ++k) {
    e += err[k];
    r += ref[k];
    out.segments.push_back({k * view_count / segments, (k + 1) * view_count / segments - 1, ratio(err[k], ref[k])});
  }
  out.overall = ratio(e, r);
  out.over_views = true;
  return out;
}

}  // namespace walkrad
