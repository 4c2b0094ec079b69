// The last round's sweeps stop on each leaf's change weighed by its display weight (solve_sweep.cpp):
// what the walkthrough sees must still converge to the tolerance, whatever the unseen leaves do.
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

// Two closed rooms back to back, each with a lamp; the views see only the first (ρ = 0.8), the second
// (ρ = 0.9) is seen by nothing and lights nothing seen. Solved at the default tolerance and at 1e-9 (the
// same links: only the last round's sweeps differ), the seen room's leaves agree within what a gain of
// 0.8 a sweep leaves after the last update (u g / (1 − g) = 4 u): 1.3e-5 measured; with the change
// weighed by 0 (every leaf taken as unseen) the last round stopped after one sweep, 1.0e-4 off.
TEST(WeighedChange, WhatTheViewsSeeConvergesToTheTolerance) {
  Scene s = test::closed_box(4.0, {0.8, 0.8, 0.8}, {0, 0, 0});
  const size_t seen_faces = s.polygons.size();
  s.materials.push_back({"bright", {0.9, 0.9, 0.9}, {0, 0, 0}});
  const uint32_t bright = uint32_t(s.materials.size() - 1);
  for (size_t k = 0; k < seen_faces; ++k) {  // the unseen room, 0.1 m along x
    Polygon p = s.polygons[k];
    for (int c = 0; c < p.count; ++c) p.v[size_t(c)].x += 4.1;
    p.material = bright;
    s.polygons.push_back(p);
  }
  s.materials.push_back({"lamp", {0, 0, 0}, {50, 50, 50}});
  for (const double x : {0.0, 4.1}) {
    Polygon lamp = test::quad({x + 1.7, 3.99, 1.7}, {x + 2.3, 3.99, 1.7}, {x + 2.3, 3.99, 2.3}, {x + 1.7, 3.99, 2.3},
                              uint32_t(s.materials.size() - 1));
    if (polygon_normal(lamp).y > 0) std::swap(lamp.v[1], lamp.v[3]);  // emits downwards
    s.polygons.push_back(lamp);
  }
  std::vector<ViewHit> hits;  // the seen room's faces, between the centre and each corner
  for (uint32_t p = 0; p < seen_faces; ++p) {
    const Polygon& poly = s.polygons[p];
    Vec3 c;
    for (int k = 0; k < poly.count; ++k) c += poly.v[k];
    for (int k = 0; k < poly.count; ++k) hits.push_back({p, (c / double(poly.count) + poly.v[k]) * 0.5, 1e-3, 0});
  }
  const ClusterTree tree = build_cluster_tree(s);
  const RayScene rays(s);
  auto solve = [&](double tolerance, Hierarchy& h, HierarchicalStats& stats) {
    h.set_view_hits(hits);
    HierarchicalSettings settings;
    settings.tolerance = tolerance;
    solve_hierarchical(h, rays, settings, stats);
  };
  Hierarchy loose(s, tree), tight(s, tree);
  HierarchicalStats loose_stats, tight_stats;
  solve(HierarchicalSettings{}.tolerance, loose, loose_stats);
  solve(1e-9, tight, tight_stats);
  ASSERT_EQ(loose_stats.oracle, "importance");
  ASSERT_TRUE(loose_stats.converged && tight_stats.converged);
  ASSERT_EQ(loose.nodes().size(), tight.nodes().size());  // the same refinement
  ASSERT_EQ(loose_stats.links, tight_stats.links);
  double worst = 0;
  size_t seen_leaves = 0;
  for (uint32_t k = 0; k < loose.nodes().size(); ++k) {
    const HNode& a = loose[k];
    if (a.cluster || a.child_count || a.polygon >= seen_faces) continue;
    ++seen_leaves;
    const double b = max_component(tight[k].B);
    worst = std::max(worst, max_component(Vec3(std::fabs(a.B.x - tight[k].B.x), std::fabs(a.B.y - tight[k].B.y),
                                               std::fabs(a.B.z - tight[k].B.z))) / b);
  }
  std::printf("%zu seen leaves, largest relative difference %.3g; last round %d and %d sweeps\n", seen_leaves, worst,
              loose_stats.iterations.back().sweeps, tight_stats.iterations.back().sweeps);
  EXPECT_GT(seen_leaves, 0u);
  EXPECT_LT(worst, 4 * HierarchicalSettings{}.tolerance);
}

}  // namespace
}  // namespace walkrad
