#include "walkrad/visibility/exposure.h"

#include <algorithm>
#include <cmath>

namespace walkrad {


Vec3 view_ray_direction(const Viewpoint& view, double sx, double sy) {
  const double h = std::tan(0.5 * view.yfov);
  const Vec3 right = normalize(cross(view.forward, view.up));
  return normalize(view.forward + right * (sx * h * view.aspect) + view.up * (sy * h));
}

double auto_exposure(const std::vector<Viewpoint>& views, const RayScene& rays, int grid,
                     const std::function<Vec3(uint32_t, const Vec3&)>& radiosity_at,
                     const std::function<bool(uint32_t)>& emits, uint64_t& rays_cast) {
  std::vector<double> seen;
  const size_t count = std::min<size_t>(views.size(), kMaxExposureViews);
  for (size_t k = 0; k < count; ++k) {
    const Viewpoint& v = views[count == views.size() ? k : k * (views.size() - 1) / std::max<size_t>(count - 1, 1)];
    for (int y = 0; y < grid; ++y)
      for (int x = 0; x < grid; ++x) {
        const double sx = 2.0 * (x + 0.5) / grid - 1.0, sy = 2.0 * (y + 0.5) / grid - 1.0;
        const RayScene::Hit hit = rays.intersect(v.position, view_ray_direction(v, sx, sy));
        ++rays_cast;
        if (hit.hit && !emits(hit.polygon)) seen.push_back(luminance(radiosity_at(hit.polygon, hit.position)) / kPi);
      }
  }
  return exposure_for(std::move(seen));
}

double exposure_for(std::vector<double> luminances) {
  if (luminances.empty()) return 1.0;
  const size_t p95 = std::min(luminances.size() - 1, size_t(0.95 * double(luminances.size())));
  std::nth_element(luminances.begin(), luminances.begin() + p95, luminances.end());
  return luminances[p95] > 0 ? 0.9 / luminances[p95] : 1.0;
}

}  // namespace walkrad
