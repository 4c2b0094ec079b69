#include "walkrad/visibility/view_grid.h"

#include <algorithm>
#include <cmath>

namespace walkrad {

Vec3 view_ray_direction(const Viewpoint& view, double sx, double sy) {
  const double h = std::tan(0.5 * view.yfov);
  const Vec3 right = normalize(cross(view.forward, view.up));
  return normalize(view.forward + right * (sx * h * view.aspect) + view.up * (sy * h));
}

Vec3 view_pixel_ray(const Viewpoint& v, int grid, int x, int y, double& weight) {
  const double sx = 2.0 * (x + 0.5) / grid - 1.0, sy = 2.0 * (y + 0.5) / grid - 1.0;
  const Vec3 d = view_ray_direction(v, sx, sy);
  const double c = dot(d, v.forward);
  weight = c * c * c;  // solid angle of a pixel of the image plane
  return d;
}

size_t spread_view(size_t k, size_t count, size_t views) {
  return count == views ? k : k * (views - 1) / std::max<size_t>(count - 1, 1);
}

}  // namespace walkrad
