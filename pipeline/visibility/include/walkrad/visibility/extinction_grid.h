// ExtinctionGrid: the volume clusters' extinction κ (volume_clusters.h) in a sparse OpenVDB FloatGrid,
// in scene units (metres; κ in 1/m), and what a segment through it keeps of the light:
//
//     T = exp(−∫ κ ds)        (Beer–Lambert; algorithms.md §7)
//
// integrated exactly over the piecewise-constant voxels by a 3D DDA (Amanatides & Woo 1987) over the
// grid's tree, after clipping the segment to the active voxels' box. Boxes are rasterised with their
// coverage of each voxel, so that ∫ κ dV (= A/4 per box) is kept whatever the voxel size.
//
// Written as extinction.vdb in the bake folder (docs/formats.md); OpenVDB's own tools (vdb_print) open it.
// OpenVDB stays inside extinction_grid.cpp: this header does not include it.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/visibility/volume_clusters.h"

namespace walkrad {

class ExtinctionGrid {
 public:
  ExtinctionGrid();
  ~ExtinctionGrid();
  ExtinctionGrid(ExtinctionGrid&&) noexcept;
  ExtinctionGrid& operator=(ExtinctionGrid&&) noexcept;

  // Half the smallest side of the boxes (each box spans two voxels or more; they are rasterised with
  // their coverage, so coarser voxels only blur their edges), coarser where that would need more
  // than 2^24 voxels.
  static double choose_voxel_size(const std::vector<VolumeBox>& boxes);
  static ExtinctionGrid build(const std::vector<VolumeBox>& boxes, double voxel_size);

  // metadata: strings stored on the grid (walkrad:*); the file's bytes depend only on the grid and them.
  void write(const std::string& path, const std::map<std::string, std::string>& metadata) const;  // OutputError
  static ExtinctionGrid read(const std::string& path);                                             // InputError
  std::string metadata(const std::string& key) const;  // "" when absent

  bool empty() const;
  double optical_depth(const Vec3& from, const Vec3& to) const;  // ∫ κ ds, thread-safe
  double transmittance(const Vec3& from, const Vec3& to) const;
  double value_at(const Vec3& p) const;  // κ of the voxel that holds p

  struct Stats {
    uint64_t active_voxels = 0;
    double voxel_size = 0;
    double kappa_min = 0, kappa_max = 0;
    Bounds bounds;  // of the active voxels, metres
    uint64_t memory_bytes = 0;
  };
  Stats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace walkrad
