// The order the solve's walks over the hierarchy rely on.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace walkrad
