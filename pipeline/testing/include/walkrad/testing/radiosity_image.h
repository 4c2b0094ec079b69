// Test helper: what a viewpoint sees of a bake's physical radiosity (BakeSampler), and the relative
// RMS difference of two such images. Comparing two bakes through the same view measures the error
// where the walkthrough looks, whatever their meshes.
#pragma once

#include <cmath>
#include <vector>

#include "walkrad/accuracy/error_measures.h"
#include "walkrad/accuracy/bake_sampler.h"

namespace walkrad::test {

// Luminance of B per pixel (grid × grid), NaN where the ray escapes.
inline std::vector<double> radiosity_image(const ChunkMesh& mesh, const Viewpoint& view, int grid) {
  return BakeSampler(mesh).luminance_image(view, grid);
}

// Relative RMS difference of two radiosity images (pixels both hit, emitters left out by a cap).
inline double relative_rms(const std::vector<double>& a, const std::vector<double>& reference, double cap) {
  std::vector<double> capped = reference;
  for (double& r : capped)
    if (r > cap) r = NAN;
  return relative_errors(a, capped).rms;
}

}  // namespace walkrad::test
