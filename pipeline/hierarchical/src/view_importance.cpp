#include "walkrad/hierarchical/view_importance.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "walkrad/visibility/exposure.h"

namespace walkrad {

Vec3 view_pixel_ray(const Viewpoint& v, int grid, int x, int y, double& weight) {
  const double sx = 2.0 * (x + 0.5) / grid - 1.0, sy = 2.0 * (y + 0.5) / grid - 1.0;
  const Vec3 d = view_ray_direction(v, sx, sy);
  const double c = dot(d, v.forward);
  weight = c * c * c;  // solid angle of a pixel of the image plane
  return d;
}

std::vector<ViewHit> cast_view_rays(const std::vector<Viewpoint>& views, const RayScene& rays, int grid, int max_views,
                                    uint64_t& rays_cast) {
  const size_t count = std::min<size_t>(views.size(), size_t(std::max(1, max_views)));
  std::vector<std::vector<ViewHit>> per_view(count);
  tbb::parallel_for(size_t(0), count, [&](size_t k) {
    const size_t index = count == views.size() ? k : k * (views.size() - 1) / std::max<size_t>(count - 1, 1);
    const Viewpoint& v = views[index];
    std::vector<ViewHit>& out = per_view[k];
    double total = 0;
    for (int y = 0; y < grid; ++y)
      for (int x = 0; x < grid; ++x) {
        double weight = 0;
        const Vec3 d = view_pixel_ray(v, grid, x, y, weight);
        total += weight;
        const RayScene::Hit hit = rays.intersect(v.position, d);
        if (hit.hit) out.push_back({hit.polygon, hit.position, weight, uint32_t(index)});
      }
    for (ViewHit& h : out) h.weight /= total * double(count);
  });
  std::vector<ViewHit> hits;
  for (auto& v : per_view) hits.insert(hits.end(), v.begin(), v.end());
  rays_cast += uint64_t(count) * uint64_t(grid) * uint64_t(grid);
  return hits;
}

}  // namespace walkrad
