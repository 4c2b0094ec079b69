// A bake's floor (z = 0, facing up) against an exact value at every vertex, as a vertex can show it
// (test_scenes.h floor_range_near): the window room's tests of the sky and of glass.
#pragma once

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "walkrad/formats/chunk.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad::test {

// Each floor vertex where f > 0 within `tolerance` (relative) of f's range about it; returns the largest
// departure, and how many vertices were checked in `seen`.
template <class F>
double expect_floor_within(const ChunkMesh& mesh, F f, double tolerance, int& seen) {
  double worst = 0;
  seen = 0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 x(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
    if (std::fabs(x.z) > 1e-6 || mesh.normals[3 * v + 2] < 0.9) continue;
    const auto [lo, hi] = floor_range_near(x, f);
    if (lo <= 0) continue;  // the floor's edge under the window: the window in its plane
    ++seen;
    const double shown = mesh.radiosity[3 * v];
    const double off = shown < lo ? (lo - shown) / lo : shown > hi ? (shown - hi) / hi : 0.0;
    worst = std::max(worst, off);
    EXPECT_LE(off, tolerance) << "at " << x.x << ", " << x.y << ": " << shown << " against " << lo << " to " << hi;
  }
  return worst;
}

}  // namespace walkrad::test
