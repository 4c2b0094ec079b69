// The last round's over-relaxed sweeps (HierarchicalSettings::relaxation, hierarchical_solver.cpp):
// where Gauss-Seidel's modes are slow they reach the plain sweeps' solution in fewer sweeps, and where
// they are fast they do not start.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/scene/cluster_tree.h"

namespace walkrad {
namespace {

// The last round's over-relaxed sweeps (HierarchicalSettings::relaxation) reach the plain sweeps'
// solution in fewer sweeps where its modes are slow, and in as many where they are fast. Closed boxes
// of ρ 0.9 lit by one end, at the default settings (the aggregation correction on) and a tolerance far
// below the default: a cube, whose modes past the overall one are fast, and a corridor 8 times as long
// as it is wide, where light crosses many elements from one end to the other.
TEST(Hierarchical, OverRelaxedSweepsReachTheSameSolutionInFewer) {
  for (const double length : {1.0, 8.0}) {
    const Scene box = test::corridor_lit_at_one_end(length, {0.9, 0.9, 0.9});
    const ClusterTree tree = build_cluster_tree(box);
    const RayScene rays(box);
    std::vector<Vec3> B[2];
    int sweeps[2];
    for (int relaxed = 0; relaxed < 2; ++relaxed) {
      Hierarchy h(box, tree);
      HierarchicalSettings s;
      s.tolerance = 1e-7;
      if (!relaxed) s.relaxation = 1.0;
      HierarchicalStats stats;
      solve_hierarchical(h, rays, s, stats);
      ASSERT_TRUE(stats.converged);
      sweeps[relaxed] = 0;  // the last round that swept (a settled round after it records none)
      for (const IterationStats& it : stats.iterations)
        if (it.sweeps > 0) sweeps[relaxed] = it.sweeps;
      for (const HNode& n : h.nodes()) B[relaxed].push_back(n.B);
    }
    ASSERT_EQ(B[0].size(), B[1].size());  // the same refinement: only the last round's sweeps differ
    double worst = 0;
    for (size_t k = 0; k < B[0].size(); ++k) {
      const Vec3 d = B[1][k] - B[0][k];
      worst = std::max(worst, std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)}) / max_component(B[0][k]));
    }
    std::printf("%g m long, %zu nodes: last round %d sweeps plain, %d over-relaxed; largest difference %.2e\n", length,
                B[0].size(), sweeps[0], sweeps[1], worst);
    EXPECT_LT(worst, 1e-5);
    if (length > 1) EXPECT_LT(sweeps[1], sweeps[0]);
    else EXPECT_LE(sweeps[1], sweeps[0]);
  }
}

}  // namespace
}  // namespace walkrad
