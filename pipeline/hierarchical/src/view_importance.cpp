#include "walkrad/hierarchical/view_importance.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "walkrad/visibility/view_grid.h"

namespace walkrad {

std::vector<ViewHit> cast_view_rays(const std::vector<Viewpoint>& views, const RayScene& rays, int grid, int max_views,
                                    uint64_t& rays_cast) {
  const size_t count = std::min<size_t>(views.size(), size_t(std::max(1, max_views)));
  std::vector<std::vector<ViewHit>> per_view(count);
  tbb::parallel_for(size_t(0), count, [&](size_t k) {
    const size_t index = spread_view(k, count, views.size());
    std::vector<ViewHit>& out = per_view[k];
    const double total = cast_view_grid(views[index], rays, grid, [&](const RayScene::Hit& hit, double weight) {
      out.push_back({hit.polygon, hit.position, weight, uint32_t(index)});
    });
    for (ViewHit& h : out) h.weight /= total * double(count);
  });
  std::vector<ViewHit> hits;
  for (auto& v : per_view) hits.insert(hits.end(), v.begin(), v.end());
  rays_cast += uint64_t(count) * uint64_t(grid) * uint64_t(grid);
  return hits;
}

}  // namespace walkrad
