// The camera of a frame: a bake's Viewpoint (scene.h) turned into the view-projection matrix the
// renderer draws with. The clip planes come from the scene bounds, so a small model and a large
// building both keep their depth precision without a per-bake setting.
#pragma once

#include "walkrad/formats/scene.h"
#include "walkrad/runtime/mat4.h"

namespace walkrad {

struct ClipPlanes {
  double near = 0;
  double far = 0;
};

// near = max(1e-3 × bounds diagonal, kMinNear); far = 4 × diagonal + the distance from the eye to
// the bounds' centre, so the whole scene stays inside from any eye that is not far outside it.
ClipPlanes clip_planes(const Viewpoint& view, const Bounds& scene_bounds);

// Projection × view for an image of the given aspect (width / height). The viewpoint's yfov is
// kept and the image's aspect used, so pixels stay square whatever size the caller renders at.
Mat4 view_projection(const Viewpoint& view, const Bounds& scene_bounds, double aspect);

}  // namespace walkrad
