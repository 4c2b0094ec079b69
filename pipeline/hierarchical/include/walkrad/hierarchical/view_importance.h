// Direct importance from the walkthrough (Smits, Arvo & Salesin 1992; algorithms.md §6): primary
// rays from the viewpoints (every frame, or an evenly spread subset of at most max_views), each hit
// weighted by the solid angle its pixel covers, cos³θ per unit image area, so that each view's
// weights sum to 1 / views. An element's direct importance R is the weight of the hits on it.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

std::vector<ViewHit> cast_view_rays(const std::vector<Viewpoint>& views, const RayScene& rays, int grid, int max_views,
                                    uint64_t& rays_cast);

}  // namespace walkrad
