#include "walkrad/visibility/exposure.h"

#include <algorithm>
#include <cmath>

namespace walkrad {

double auto_exposure(const std::vector<Viewpoint>& views, const RayScene& rays, int grid,
                     const std::function<Vec3(uint32_t, const Vec3&)>& radiosity_at,
                     const std::function<bool(uint32_t)>& emits, uint64_t& rays_cast) {
  std::vector<double> seen;
  const size_t count = std::min<size_t>(views.size(), kMaxExposureViews);
  for (size_t k = 0; k < count; ++k) {
    cast_view_grid(views[spread_view(k, count, views.size())], rays, grid, [&](const RayScene::Hit& hit, double) {
      if (!emits(hit.polygon)) seen.push_back(luminance(radiosity_at(hit.polygon, hit.position)) / kPi);
    });
    rays_cast += uint64_t(grid) * uint64_t(grid);
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
