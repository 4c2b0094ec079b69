// Multi-resolution visibility (Sillion & Drettakis 1995, "Feature-based control of visibility error";
// algorithms.md §7). Between two linked nodes, a volume cluster (volume_clusters.h) stands in for
// its polygons, as a medium of extinction κ, when its objects are small against the shadow they would
// cast: their size f below the width of the link's penumbra at the cluster,
//
//     f < ratio × w,   w = (s_i d_j + s_j d_i) / (d_i + d_j)
//
// (s_i, s_j: the two ends' sizes; d_i, d_j: their distances to the cluster's centre). w is the width
// at the cluster of the bundle of segments joining the two ends: a blocker smaller than it casts no
// umbra on the receiver (the source's penumbra, s_j d_i / d_j at the receiver, is wider than its
// shadow), or its shadow is averaged over a receiver larger than it. Otherwise exact Embree rays.
//
// A link that sees through volumes casts its rays against the scene without the volumes' polygons
// (the solid scene) and multiplies each ray's visibility by the transmittance exp(−∫ κ ds) through the
// extinction grid; a link whose shaft holds only volumes casts no ray at all.
#pragma once

#include <cstdint>

#include "walkrad/formats/vec3.h"
#include "walkrad/visibility/extinction_grid.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/visibility/volume_clusters.h"

namespace walkrad {

struct VolumeVisibility {
  const VolumeClusters* clusters = nullptr;
  const ExtinctionGrid* grid = nullptr;
  const RayScene* solid = nullptr;  // the scene without the volume clusters' polygons
  double penumbra_ratio = 1.0;
};

// The width at `at` of the bundle of segments between two ends of sizes s_i, s_j centred at ci, cj.
inline double penumbra_width(const Vec3& ci, double si, const Vec3& cj, double sj, const Vec3& at) {
  const double di = length(at - ci), dj = length(at - cj);
  return di + dj > 0 ? (si * dj + sj * di) / (di + dj) : std::max(si, sj);
}

}  // namespace walkrad
