// The parallel walks over a hierarchy (hierarchy_walk.h) and the passes built on them: each node once,
// after its children (or its parent), and the bits of the serial passes they replaced.
#include <atomic>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "walkrad/hierarchical/cluster_radiosity.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/hierarchical/hierarchy_walk.h"
#include "walkrad/hierarchical/link_transport.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

// 1,400 cubes (8,400 polygons: subtrees above kParallelPolygons go to other threads), a third of
// their faces split once and some of those twice, radiosity and send factors at random.
struct Cubes {
  Scene scene;
  ClusterTree tree;
  Hierarchy h;
  Cubes() : scene(make()), tree(build_cluster_tree(scene)), h(scene, tree) {
    for (uint32_t k = 0; k < h.nodes().size(); ++k)
      if (!h[k].cluster && (h[k].depth == 0 ? k % 3 == 0 : k % 7 == 0) && h[k].depth < 2) h.subdivide(k);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (HNode& n : h.nodes()) {
      n.B = Vec3(u(rng), u(rng), u(rng));
      n.send = 0.5 + u(rng);
    }
  }
  static Scene make() {
    Scene s;
    s.materials.push_back({"grey", {0.5, 0.5, 0.5}, {0, 0, 0}});
    for (int k = 0; k < 1400; ++k) test::add_cube(s, {1.5 * (k % 40), 0.3 * (k % 7), 1.5 * (k / 40)}, 1.0);
    return s;
  }
};

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

TEST(HierarchyWalk, BottomUpVisitsEachNodeOnceAfterItsChildren) {
  const Cubes c;
  const Hierarchy& h = c.h;
  ASSERT_GE(h.polygon_count(h[h.root()]), 2 * kParallelPolygons);
  ASSERT_GT(h.nodes().size(), h.made_at_start());  // split elements too
  std::vector<std::atomic<uint32_t>> when(h.nodes().size());
  std::atomic<uint32_t> clock{0};
  tbb::task_arena(2).execute([&] { nodes_bottom_up(h, [&](uint32_t k) { when[k] = ++clock; }); });
  ASSERT_EQ(clock.load(), h.nodes().size());
  for (uint32_t k = 0; k < h.nodes().size(); ++k) {
    ASSERT_NE(when[k].load(), 0u) << "node " << k;
    for (uint32_t j = 0; j < h[k].child_count; ++j) ASSERT_LT(when[h.child(h[k], j)].load(), when[k].load()) << "node " << k;
  }
}

TEST(HierarchyWalk, TopDownHandsEachClusterItsParentsState) {
  const Cubes c;
  const Hierarchy& h = c.h;
  std::vector<std::atomic<int64_t>> above(h.nodes().size());
  for (auto& a : above) a = -2;
  tbb::task_arena(2).execute([&] {
    clusters_top_down(h, h.root(), int64_t(-1), [&](uint32_t k, const int64_t& parent) {
      above[k] = parent;
      return int64_t(k);
    });
  });
  for (uint32_t k = 0; k < h.nodes().size(); ++k)
    EXPECT_EQ(above[k].load(), h[k].cluster ? int64_t(h[k].parent) : int64_t(-2)) << "node " << k;
}

// The passes as one serial walk in reverse node order (children come after their parents) gave them.
TEST(HierarchyWalk, PullUpAndFacingRadiosityGiveTheSerialPassesBits) {
  Cubes c;
  Hierarchy& h = c.h;
  HNodes serial = h.nodes();
  for (size_t k = serial.size(); k-- > 0;) {
    HNode& n = serial[k];
    if (n.child_count == 0) {
      if (!n.cluster) n.Bt = n.B * n.send;
      continue;
    }
    Vec3 b, bt;
    for (uint32_t j = 0; j < n.child_count; ++j) {
      const HNode& child = serial[h.child(n, j)];
      b += child.B * child.area;
      bt += child.Bt * child.area;
    }
    n.B = n.area > 0 ? b / n.area : Vec3{};
    n.Bt = n.area > 0 ? bt / n.area : Vec3{};
  }
  tbb::task_arena(2).execute([&] { pull_up_radiosity(h); });
  for (size_t k = 0; k < serial.size(); ++k) {
    ASSERT_TRUE(same_bits(h[uint32_t(k)].B, serial[k].B)) << "node " << k;
    ASSERT_TRUE(same_bits(h[uint32_t(k)].Bt, serial[k].Bt)) << "node " << k;
  }
  std::vector<std::array<Vec3, 6>> expected(h.cluster_count()), facing;
  for (size_t k = h.made_at_start(); k-- > 0;)
    if (h[uint32_t(k)].cluster)
      expected[h[uint32_t(k)].tree_node] = facing_from_children(h, uint32_t(k), expected, [&](uint32_t i) { return h[i].Bt; });
  tbb::task_arena(2).execute([&] { facing_radiosity(h, [&](uint32_t i) { return h[i].Bt; }, facing); });
  ASSERT_EQ(facing.size(), expected.size());
  for (size_t t = 0; t < facing.size(); ++t)
    for (size_t a = 0; a < 6; ++a) ASSERT_TRUE(same_bits(facing[t][a], expected[t][a])) << "cluster " << t;
}

}  // namespace
}  // namespace walkrad
