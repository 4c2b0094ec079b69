// Camera (camera.h): clip planes from the scene bounds and the view-projection matrix.
#include "walkrad/runtime/camera.h"

#include <algorithm>

namespace walkrad {

namespace {
// Below this (metres) depth precision is wasted on nothing: no bake has detail that small.
constexpr double kMinNear = 1e-4;
}  // namespace

ClipPlanes clip_planes(const Viewpoint& view, const Bounds& scene_bounds) {
  const double diagonal = length(scene_bounds.diagonal());
  const double distance = scene_bounds.empty() ? 0.0 : length(scene_bounds.center() - view.position);
  ClipPlanes c;
  c.near = std::max(1e-3 * diagonal, kMinNear);
  // An empty or point-sized scene would give far <= near, which the projection cannot represent.
  c.far = std::max(4.0 * diagonal + distance, 2.0 * c.near);
  return c;
}

Mat4 view_projection(const Viewpoint& view, const Bounds& scene_bounds, double aspect) {
  const ClipPlanes c = clip_planes(view, scene_bounds);
  return perspective(view.yfov, aspect, c.near, c.far) * view_matrix(view.position, view.forward, view.up);
}

}  // namespace walkrad
