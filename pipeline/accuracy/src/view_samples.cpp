#include "walkrad/accuracy/view_samples.h"

#include <algorithm>
#include <cmath>

#include "walkrad/visibility/exposure.h"
#include "walkrad/core/sampling.h"

namespace walkrad {

std::vector<uint32_t> spread_views(size_t view_count, size_t count) {
  count = std::min(count, view_count);
  std::vector<uint32_t> out;
  for (size_t k = 0; k < count; ++k)
    out.push_back(uint32_t(count == view_count ? k : k * (view_count - 1) / std::max<size_t>(count - 1, 1)));
  return out;
}

std::vector<ViewRay> stratified_view_rays(const std::vector<Viewpoint>& views, size_t max_views, size_t rays_per_view,
                                          uint64_t seed) {
  const std::vector<uint32_t> chosen = spread_views(views.size(), max_views);
  std::vector<ViewRay> out;
  for (uint32_t index : chosen) {
    const Viewpoint& v = views[index];
    const int rows = std::max(1, int(std::lround(std::sqrt(double(rays_per_view) / std::max(v.aspect, 1e-3)))));
    const int cols = std::max(1, int(std::lround(double(rays_per_view) / rows)));
    const size_t first = out.size();
    double total = 0;
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < cols; ++x) {
        Rng rng(seed, uint64_t(index) * uint64_t(rows * cols) + uint64_t(y * cols + x));
        const double sx = 2.0 * (x + rng.uniform()) / cols - 1.0, sy = 2.0 * (y + rng.uniform()) / rows - 1.0;
        const Vec3 d = view_ray_direction(v, sx, sy);
        const double c = dot(d, v.forward);
        out.push_back({index, v.position, d, c * c * c});
        total += c * c * c;
      }
    for (size_t k = first; k < out.size(); ++k) out[k].weight /= total * double(chosen.size());
  }
  return out;
}

std::vector<ViewRay> image_rays(const std::vector<Viewpoint>& views, uint32_t view, int width, int& height) {
  const Viewpoint& v = views.at(view);
  height = std::max(1, int(std::lround(width / std::max(v.aspect, 1e-3))));
  std::vector<ViewRay> out;
  for (int y = height - 1; y >= 0; --y)  // top row first, as images are stored
    for (int x = 0; x < width; ++x) {
      const Vec3 d = view_ray_direction(v, 2.0 * (x + 0.5) / width - 1.0, 2.0 * (y + 0.5) / height - 1.0);
      const double c = dot(d, v.forward);
      out.push_back({view, v.position, d, c * c * c});
    }
  return out;
}

}  // namespace walkrad
