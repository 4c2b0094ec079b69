// `walkrad diff A B`: do two bake folders hold the same result, within a tolerance, and if not, how do
// they differ? Used by golden-file tests (tests/golden/) and by users comparing settings or versions.
//
// Manifests: chunk count, triangle totals, viewpoints, exposure (relative), settings (key by key),
// scene hash. Surfaces: every vertex of A is matched to a vertex of B at the same position (within
// position_tolerance × the diagonal of A's bounds) with the same normal; unmatched vertices mean the
// geometry or the meshing differs. Radiosity (_RADIOSITY) over matched vertices: relative RMS
// sqrt(Σ|B_A − B_B|² / Σ|B_A|²) and the largest difference relative to A's largest radiosity.
#pragma once

#include <string>
#include <vector>

namespace walkrad {

struct DiffSettings {
  double tolerance = 1e-3;           // radiosity: relative RMS and relative largest difference
  double position_tolerance = 1e-4;  // fraction of the bake's diagonal (Draco quantises to 1e-5 by default)
};

struct BakeDiff {
  std::vector<std::string> differences;  // one sentence each; empty: the bakes agree
  std::vector<std::string> notes;        // differences that do not count (timings, paths, tool version)
  size_t vertices_a = 0, vertices_b = 0, unmatched = 0;
  double radiosity_rms = 0, radiosity_max = 0;  // relative, over matched vertices
  bool same() const { return differences.empty(); }
};

// Throws InputError when either folder is not a readable bake.
BakeDiff diff_bakes(const std::string& a, const std::string& b, const DiffSettings& settings);

}  // namespace walkrad
