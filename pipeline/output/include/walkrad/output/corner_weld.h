// The mesher's weld (surface_mesher.h): corners closer than a tolerance become one vertex, and the
// grid of cells that finds a point's neighbours, sorted rather than hashed so that many threads
// build and read it.
//
// The weld's rule is sequential, first come first numbered: corner n takes the first point made
// before it that lies within tol, "first" as a scan of the 27 cells of side tol around it (z, then y,
// then x, each from −1 to 1) and of each cell's points in the order they were made would meet them;
// with none, it makes a new point. weld_corners gives that result without the scan: bit-identical
// corners are grouped by a sort, each distinct position's neighbours within tol are found in
// parallel (almost always none), and only the choice among them is made in corner order. (Scanning a
// hash grid of cells, corner by corner, would be the 150-room level's largest serial step of its mesh
// phase.)
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "walkrad/formats/vec3.h"

namespace walkrad {

struct CellKey {
  int64_t x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
  bool operator<(const CellKey& o) const { return x != o.x ? x < o.x : y != o.y ? y < o.y : z < o.z; }
};

// The cell of side `cell` that holds p.
inline CellKey cell_of(const Vec3& p, double cell) {
  return {int64_t(std::floor(p.x / cell)), int64_t(std::floor(p.y / cell)), int64_t(std::floor(p.z / cell))};
}

// Points in cells of a uniform grid: the (cell, id) pairs sorted, so that a cell's ids are one
// ascending run found by binary search. Built once (in parallel), then read by any number of threads.
class CellIndex {
 public:
  CellIndex(const std::vector<Vec3>& points, double cell);
  CellKey key(const Vec3& p) const { return cell_of(p, cell_); }
  // The ids in cells first..last along z (x and y fixed), ascending by cell, then by id.
  std::pair<const uint32_t*, const uint32_t*> in(const CellKey& first, int64_t last_z) const;
  std::pair<const uint32_t*, const uint32_t*> in(const CellKey& k) const { return in(k, k.z); }

 private:
  double cell_;
  std::vector<CellKey> keys_;  // sorted
  std::vector<uint32_t> ids_;  // beside keys_
};

struct WeldedCorners {
  std::vector<Vec3> points;        // in the order they were made
  std::vector<uint32_t> point_of;  // by corner
};

// Deterministic whatever the thread count: the result of the sequential rule above.
WeldedCorners weld_corners(const std::vector<Vec3>& corners, double tol);

}  // namespace walkrad
