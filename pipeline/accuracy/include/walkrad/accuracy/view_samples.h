// Where the sweep measures error: rays from the walkthrough's viewpoints (docs/accuracy.md).
//  - stratified_view_rays: up to max_views viewpoints spread evenly along the walkthrough; on each, a
//    grid of cells over the image (columns ≈ rows × aspect), one ray through a random point of each
//    cell (stream Rng(seed, view × cells + cell)). Weight: the solid angle of the image area the ray
//    stands for, cos³θ per unit image area (as view_importance.h), each view's weights summing to
//    1 / views: how much of the walkthrough's view a point stands for.
//  - image_rays: the pixel centres of a width × height image of one view (height = width / aspect).
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/scene.h"

namespace walkrad {

struct ViewRay {
  uint32_t view = 0;  // index into the viewpoints
  Vec3 origin, direction;
  double weight = 0;
};

std::vector<ViewRay> stratified_view_rays(const std::vector<Viewpoint>& views, size_t max_views, size_t rays_per_view,
                                          uint64_t seed);

std::vector<ViewRay> image_rays(const std::vector<Viewpoint>& views, uint32_t view, int width, int& height);

// Indices of up to `count` viewpoints spread evenly along the walkthrough (first and last included).
std::vector<uint32_t> spread_views(size_t view_count, size_t count);

}  // namespace walkrad
