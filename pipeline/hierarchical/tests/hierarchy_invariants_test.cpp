// The invariants a solve's rounds keep (hierarchy_invariants.h; checked after every round in debug and
// sanitizer builds): they hold after a solve, and each kind of fault is named when it is made.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "walkrad/core/invariant.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy_invariants.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

// A closed room lit by a ceiling lamp, a cube on its floor, solved with the defaults.
struct Solved {
  Scene scene = test::closed_box(2.0, {0.6, 0.6, 0.6}, {0, 0, 0});
  ClusterTree tree;
  std::unique_ptr<RayScene> rays;
  std::unique_ptr<Hierarchy> h;
  Solved() {
    scene.materials.push_back({"lamp", {0, 0, 0}, {20, 20, 20}});
    Polygon lamp = test::quad({0.8, 1.99, 0.8}, {1.2, 1.99, 0.8}, {1.2, 1.99, 1.2}, {0.8, 1.99, 1.2}, 1);
    if (polygon_normal(lamp).y > 0) std::swap(lamp.v[1], lamp.v[3]);
    scene.polygons.push_back(lamp);
    test::add_cube(scene, {1.0, 0.3, 1.0}, 0.6);  // something to cluster and to cast a shadow
    tree = build_cluster_tree(scene);
    rays = std::make_unique<RayScene>(scene);
    h = std::make_unique<Hierarchy>(scene, tree);
    HierarchicalSettings settings;
    HierarchicalStats stats;
    solve_hierarchical(*h, *rays, settings, stats);
  }
  // An element with children, and a node with links.
  uint32_t split_element() const {
    for (uint32_t i = 0; i < h->nodes().size(); ++i)
      if (!(*h)[i].cluster && (*h)[i].child_count) return i;
    return UINT32_MAX;
  }
  uint32_t linked() const {
    for (uint32_t i = 0; i < h->nodes().size(); ++i)
      if (!(*h)[i].links.empty()) return i;
    return UINT32_MAX;
  }
};

TEST(HierarchyInvariants, HoldAfterASolve) {
  const Solved s;
  EXPECT_EQ(hierarchy_fault(*s.h), "");
  ASSERT_NE(s.split_element(), UINT32_MAX);  // the checks below have something to break
  ASSERT_NE(s.linked(), UINT32_MAX);
}

TEST(HierarchyInvariants, EachFaultIsNamed) {
  {
    Solved s;
    const uint32_t e = s.split_element();
    (*s.h)[s.h->child((*s.h)[e], 2)].parent = int32_t(e) - 1;
    EXPECT_NE(hierarchy_fault(*s.h).find("names parent"), std::string::npos) << hierarchy_fault(*s.h);
  }
  {
    Solved s;
    (*s.h)[s.split_element()].area *= 1.001;
    EXPECT_NE(hierarchy_fault(*s.h).find("children's"), std::string::npos) << hierarchy_fault(*s.h);
  }
  {
    Solved s;
    (*s.h)[s.linked()].links[0].source = uint32_t(s.h->nodes().size());
    EXPECT_NE(hierarchy_fault(*s.h).find("out of range"), std::string::npos) << hierarchy_fault(*s.h);
  }
  {
    Solved s;
    (*s.h)[s.linked()].links[0].F = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(hierarchy_fault(*s.h).find("has F"), std::string::npos) << hierarchy_fault(*s.h);
  }
  {
    Solved s;
    (*s.h)[s.linked()].B.y = std::numeric_limits<double>::infinity();
    EXPECT_NE(hierarchy_fault(*s.h).find("not finite"), std::string::npos) << hierarchy_fault(*s.h);
  }
}

TEST(HierarchyInvariantsDeathTest, ABrokenInvariantEndsTheProcessSayingWhere) {
  EXPECT_DEATH(invariant_broken("solver.cpp", 12, "a link out of range"),
               "walkrad: invariant broken at solver.cpp:12: a link out of range");
}

}  // namespace
}  // namespace walkrad
