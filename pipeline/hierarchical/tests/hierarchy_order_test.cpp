// The order the solve's walks over the hierarchy rely on.
#include <cstdint>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

// What the cluster-indexed sums rely on, clusters numbered 0 .. cluster_count() − 1 by tree_node, one
// each; and the order Hierarchy documents for made_at_start(): preorder (walking the nodes with a stack
// of clusters, every cluster's and element root's parent is on it), all before any element split.
TEST(Hierarchy, ClustersAreNumberedByTreeNodeAndMadeInPreorder) {
  Scene scene;
  scene.materials.push_back({"grey", {0.5, 0.5, 0.5}, {0, 0, 0}});
  for (int k = 0; k < 6; ++k) test::add_cube(scene, {1.5 * k, 0.3 * k, 0}, 1.0);
  const ClusterTree tree = build_cluster_tree(scene);
  Hierarchy h(scene, tree);
  ASSERT_GT(h.cluster_count(), size_t(8));
  for (uint32_t k = 0; k < h.nodes().size(); ++k)  // split some elements: they come after
    if (!h[k].cluster && h[k].depth == 0 && k % 3 == 0) h.subdivide(k);
  std::vector<int> seen(h.cluster_count(), 0);
  std::vector<uint32_t> path;
  size_t made = 0;
  for (uint32_t k = 0; k < h.nodes().size(); ++k) {
    const HNode& n = h[k];
    if (!n.cluster && n.depth != 0) continue;
    made = k + 1;
    while (!path.empty() && int64_t(path.back()) != int64_t(n.parent)) path.pop_back();
    ASSERT_EQ(n.parent >= 0, !path.empty()) << "node " << k;
    if (!n.cluster) continue;
    ASSERT_LT(n.tree_node, h.cluster_count());
    ++seen[n.tree_node];
    path.push_back(k);
  }
  for (size_t c = 0; c < seen.size(); ++c) EXPECT_EQ(seen[c], 1) << "cluster " << c;
  EXPECT_EQ(made, h.made_at_start());
  EXPECT_EQ(h.made_at_start(), h.cluster_count() + scene.polygons.size());
}

// Hierarchy::sample names the child holding the point it draws from the tree's layout, not from the
// children's nodes: every point drawn from a cluster lies in the child it names (within its bounds,
// on the surface of that child's polygons), a leaf cluster's elements and a node's two halves alike.
TEST(Hierarchy, SampleNamesTheChildThatHoldsThePoint) {
  Scene scene;
  scene.materials.push_back({"grey", {0.5, 0.5, 0.5}, {0, 0, 0}});
  for (int k = 0; k < 40; ++k) test::add_cube(scene, {1.5 * (k % 8), 0.3 * (k % 3), 1.5 * (k / 8)}, 1.0 + 0.1 * (k % 4));
  const ClusterTree tree = build_cluster_tree(scene);
  const Hierarchy h(scene, tree);
  size_t leaf_clusters = 0;
  for (uint32_t k = 0; k < h.nodes().size(); ++k) {
    const HNode& n = h[k];
    if (!n.cluster) continue;
    leaf_clusters += tree.nodes[n.tree_node].leaf();
    for (int s = 0; s < 64; ++s) {
      const double w = (s + 0.5) / 64, u = 0.37, v = 0.61;
      Vec3 point, normal;
      uint32_t child = UINT32_MAX;
      h.sample(n, u, v, w, point, normal, &child);
      ASSERT_LT(child, n.child_count) << "cluster " << k;
      const HNode& kid = h[h.child(n, child)];
      const Bounds& b = kid.bounds;
      const double e = 1e-12 * (1 + length(point));
      for (int a = 0; a < 3; ++a) {
        ASSERT_GE(point[a], b.lo[a] - e) << "cluster " << k << " sample " << s;
        ASSERT_LE(point[a], b.hi[a] + e) << "cluster " << k << " sample " << s;
      }
      if (!kid.cluster) EXPECT_NEAR(dot(point - kid.shape.v[0], kid.normal), 0.0, 1e-12) << "cluster " << k;
    }
  }
  EXPECT_GT(leaf_clusters, size_t(10));
}

// build_cluster_tree builds halves of 16,384 polygons or more on two threads, at indices fixed by the
// counts: the same tree as on one thread, in preorder (child 0 next), child 0 holding the first half
// of its node's slots (what Hierarchy::sample relies on).
TEST(ClusterTree, OneThreadAndTwoBuildTheSameTree) {
  Scene scene;
  scene.materials.push_back({"grey", {0.5, 0.5, 0.5}, {0, 0, 0}});
  for (int k = 0; k < 6000; ++k) test::add_cube(scene, {1.5 * (k % 60), 0.3 * (k % 7), 1.5 * (k / 60)}, 1.0);
  ASSERT_GT(scene.polygons.size(), size_t(2 * 16384));
  ClusterTree one, two;
  tbb::task_arena(1).execute([&] { one = build_cluster_tree(scene); });
  tbb::task_arena(2).execute([&] { two = build_cluster_tree(scene); });
  ASSERT_EQ(one.nodes.size(), two.nodes.size());
  EXPECT_EQ(one.polygons, two.polygons);
  EXPECT_EQ(one.slot, two.slot);
  for (size_t k = 0; k < one.nodes.size(); ++k) {
    const ClusterNode &a = one.nodes[k], &b = two.nodes[k];
    ASSERT_TRUE(a.first == b.first && a.count == b.count && a.child[0] == b.child[0] && a.child[1] == b.child[1]) << "node " << k;
    ASSERT_EQ(std::memcmp(&a.bounds, &b.bounds, sizeof(Bounds)), 0) << "node " << k;
    ASSERT_EQ(std::memcmp(&a.area, &b.area, sizeof(double)), 0) << "node " << k;
    if (a.leaf()) continue;
    EXPECT_EQ(a.child[0], int32_t(k + 1)) << "node " << k;
    const ClusterNode &low = one.nodes[size_t(a.child[0])], &high = one.nodes[size_t(a.child[1])];
    EXPECT_TRUE(low.first == a.first && low.count == a.count / 2) << "node " << k;
    EXPECT_TRUE(high.first == a.first + a.count / 2 && high.count == a.count - a.count / 2) << "node " << k;
  }
}

}  // namespace
}  // namespace walkrad
