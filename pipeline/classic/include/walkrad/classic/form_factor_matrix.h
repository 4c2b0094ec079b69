// The classic method's form factor matrix (algorithms.md §2-3): F_ij for every pair of elements,
// by quadrature of the point-to-polygon contour formula over the receiver, each quadrature point
// weighted by the fraction of Embree rays from it to stratified points of the source that arrive.
// Rows are computed in parallel, each with its own random streams: the matrix does not depend on
// the thread count. Stored sparse (zero pairs are dropped), one row per receiver.
// Shaft culling (shaft.h) decides which pairs need rays at all: per pair of input polygons, the
// polygons that may stand between them; per receiver element and source polygon, that list filtered
// by their own shaft. An empty list means visibility 1 without a ray.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "walkrad/scene/cluster_tree.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/classic/subdivision.h"

namespace walkrad {

struct FormFactorMatrix {
  std::vector<uint64_t> row_start;  // row i holds entries [row_start[i], row_start[i+1])
  std::vector<uint32_t> column;
  std::vector<double> value;

  size_t rows() const { return row_start.empty() ? 0 : row_start.size() - 1; }
  double row_sum(size_t i) const;
};

struct FormFactorSettings {
  int rays_per_point = 1;      // visibility rays from each receiver quadrature point
  bool visibility = true;      // false: unoccluded form factors (no rays)
  // > 0: the hemicube instead (Cohen & Greenberg 1985; hemicube.h) at each element's centroid, this
  // many pixels on its top face's side: F_ij from the point, visibility from its z-buffer over every
  // element (the classic method as the 1980s ran it, for comparison in walkrad sweep).
  int hemicube = 0;
  // When set, every visibility segment cast is appended here in row order (bench/ replays them).
  std::vector<RayScene::Segment>* record = nullptr;
};

struct FormFactorCounts {
  uint64_t pairs = 0;    // element pairs that face each other
  uint64_t unoccluded = 0;  // pairs whose shaft holds no candidate occluder: no rays cast
  uint64_t nonzero = 0;  // entries kept
  uint64_t rays = 0;     // visibility rays cast
};

// rays: null for unoccluded form factors. tree: the cluster tree over the same scene's polygons, for
// shaft culling; null casts rays for every pair. progress(rows_done) is called from worker threads.
// With settings.hemicube, rays and tree are unused (counts.rays stays 0).
FormFactorMatrix compute_form_factors(const Subdivision& sub, const RayScene* rays, const ClusterTree* tree,
                                      const FormFactorSettings& settings, FormFactorCounts& counts,
                                      const std::function<void(size_t)>& progress = {});

}  // namespace walkrad
