// Automatic exposure from what the walkthrough sees. Primary rays from the viewpoints (a grid per
// view, at most kMaxExposureViews views, evenly spread along the walkthrough) find the surfaces on
// screen; the exposure maps the 95th percentile of their luminance (radiance B/π, emitters left
// out: a light may clip to white) to display value 0.9. Display colour = B/π × exposure.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "walkrad/visibility/ray_scene.h"
#include "walkrad/visibility/view_grid.h"

namespace walkrad {

constexpr int kMaxExposureViews = 64;

// radiosity_at(polygon, point) → B there; emits(polygon) → true for emitters.
double auto_exposure(const std::vector<Viewpoint>& views, const RayScene& rays, int grid,
                     const std::function<Vec3(uint32_t, const Vec3&)>& radiosity_at,
                     const std::function<bool(uint32_t)>& emits, uint64_t& rays_cast);

// The exposure mapping the 95th percentile of these luminances (B/π) to 0.9; 1 when there are none or
// all are dark. For bakes without viewpoints, over the surfaces themselves.
double exposure_for(std::vector<double> luminances);

}  // namespace walkrad
