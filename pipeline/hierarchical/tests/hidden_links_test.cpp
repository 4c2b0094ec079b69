// Links that see nothing: a link whose every ray is blocked carries 0, is cast again once with more
// rays, and is then settled where it is (Solver::settled_hidden, docs/numerics.md "Leaks through links").
#include <cstdio>

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/scene/cluster_tree.h"

namespace walkrad {
namespace {

// Two closed rooms back to back, a wall 0.1 m thick between them, a lamp under the lit room's ceiling.
// Links across the wall see nothing: every ray is blocked, cast again with more rays, blocked again,
// and the link is settled at 0 where it is (Solver::settled_hidden). Split further, or sent down to
// the children of a lit element that splits for the lamp's sake, each level cast 4 times the rays to
// find nothing (office-floor's 16 rooms: 3.2 M links between its wings, 123 M of its 882 M rays).
TEST(Hierarchical, ALinkThroughAWallIsSettledNotRefined) {
  Scene s = test::closed_box(4.0, {0.6, 0.6, 0.6}, {0, 0, 0});
  const size_t lit_faces = s.polygons.size();
  for (size_t k = 0; k < lit_faces; ++k) {  // the dark room, 0.1 m along x
    Polygon p = s.polygons[k];
    for (int c = 0; c < p.count; ++c) p.v[size_t(c)].x += 4.1;
    s.polygons.push_back(p);
  }
  const size_t dark_end = s.polygons.size();
  s.materials.push_back({"lamp", {0, 0, 0}, {50, 50, 50}});
  Polygon lamp = test::quad({1.7, 3.99, 1.7}, {2.3, 3.99, 1.7}, {2.3, 3.99, 2.3}, {1.7, 3.99, 2.3}, 1);
  if (polygon_normal(lamp).y > 0) std::swap(lamp.v[1], lamp.v[3]);  // emits downwards
  s.polygons.push_back(lamp);
  for (const double error : {HierarchicalSettings{}.error, 0.05}) {
    const ClusterTree tree = build_cluster_tree(s);
    const RayScene rays(s);
    Hierarchy h(s, tree);
    HierarchicalSettings settings;
    settings.error = error;
    HierarchicalStats stats;
    solve_hierarchical(h, rays, settings, stats);
    auto dark = [&](const HNode& n) { return !n.cluster && n.polygon >= lit_faces && n.polygon < dark_end; };
    size_t lit_splits = 0, across = 0, across_below = 0;
    for (const HNode& n : h.nodes()) {
      if (n.cluster) continue;
      if (dark(n)) {
        EXPECT_EQ(n.child_count, 0u) << "a dark room's element split, --error " << error;
        EXPECT_EQ(max_component(n.B), 0.0);
      } else if (n.child_count) {
        ++lit_splits;
      }
      for (const Link& l : n.links) {
        const HNode& src = h[l.source];
        const bool src_dark = src.cluster ? src.bounds.lo.x > 4.05 : dark(src);
        if (src_dark == dark(n) || src.bounds.hi.x > 4.05 && src.bounds.lo.x < 4.05) continue;
        ++across;
        across_below += n.depth > 0;
        EXPECT_EQ(l.F, 0.0);
      }
    }
    std::printf("--error %.2f: %zu lit elements split, %zu links across the wall (%zu below a root), %llu rays\n", error,
                lit_splits, across, across_below, static_cast<unsigned long long>(stats.rays));
    EXPECT_GT(lit_splits, 0u);  // the lamp's light varies over the lit room: its elements split
    EXPECT_GT(across, 0u);
    EXPECT_EQ(across_below, 0u) << "--error " << error;
  }
}

}  // namespace
}  // namespace walkrad
