// The primary rays of a walkthrough's views, written once for every stage that casts them (importance,
// exposure, the chunks' importance): a grid × grid image per view, a ray through each pixel's centre,
// weighted by the solid angle the pixel covers, cos³θ per unit image area (the image plane at unit
// distance: dω = cos³θ dA).
#pragma once

#include <cstddef>
#include <cstdint>

#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

// Direction through a point of the image, (sx, sy) in [-1, 1] from left/bottom to right/top.
Vec3 view_ray_direction(const Viewpoint& view, double sx, double sy);

// The ray through pixel (x, y) of a grid² image of the view, and its weight cos³θ.
Vec3 view_pixel_ray(const Viewpoint& v, int grid, int x, int y, double& weight);

// The k-th of `count` views spread evenly along `views` of them (all of them, in order, when count is
// views): the first and the last always among them.
size_t spread_view(size_t k, size_t count, size_t views);

// Casts the view's grid² rays, row by row, and calls on_hit(hit, weight) for each that meets a surface.
// Returns the sum of all the rays' weights (hit or not), by which a view's weights are made shares.
template <class OnHit>
double cast_view_grid(const Viewpoint& v, const RayScene& rays, int grid, OnHit&& on_hit) {
  double total = 0;
  for (int y = 0; y < grid; ++y)
    for (int x = 0; x < grid; ++x) {
      double weight = 0;
      const Vec3 d = view_pixel_ray(v, grid, x, y, weight);
      total += weight;
      const RayScene::Hit hit = rays.intersect(v.position, d);
      if (hit.hit) on_hit(hit, weight);
    }
  return total;
}

}  // namespace walkrad
