// aggregation_correction (link_transport.h) with the buffers a solve keeps between calls: the same
// bits as a call with its own, whatever a larger hierarchy left in them before.
#include <cstdio>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/hierarchical/link_transport.h"
#include "walkrad/scene/cluster_tree.h"

namespace walkrad {
namespace {

// A corridor of ρ 0.9 lit at one end, `length` long, with rows of small cubes along its middle
// (clusters, linked as such).
Scene corridor_with_cubes(double length) {
  Scene box = test::corridor_lit_at_one_end(length, {0.9, 0.9, 0.9});
  for (int x = 0; x < 3; ++x)
    for (int z = 0; z < int(4 * length); ++z) test::add_cube(box, {0.3 + 0.2 * x, 0.5, 0.125 + 0.25 * z}, 0.04);
  return box;
}

// That corridor solved at the default settings, then its reflected light set 30% low: a level the
// correction has to lift.
struct DarkBox {
  Scene scene;
  ClusterTree tree;
  Hierarchy h;
  explicit DarkBox(double length) : scene(corridor_with_cubes(length)), tree(build_cluster_tree(scene)), h(scene, tree) {
    const RayScene rays(scene);
    HierarchicalStats stats;
    solve_hierarchical(h, rays, HierarchicalSettings{}, stats);
    for (HNode& n : h.nodes())
      if (is_leaf_element(n)) n.B = n.emission + (n.B - n.emission) * 0.7;
    pull_up_radiosity(h);
  }
};

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

TEST(LinkTransport, AggregationCorrectionWithKeptBuffersGivesTheSameBits) {
  DarkBox long_box(8.0);
  const DarkBox short_box(2.0);
  Hierarchy& large = long_box.h;
  const Hierarchy& small = short_box.h;
  ASSERT_GT(large.nodes().size(), small.nodes().size());
  size_t cluster_links = 0;  // what gathers by direction (the buffers' cube) is in play
  for (const HNode& n : small.nodes()) cluster_links += n.cluster ? n.links.size() : 0;
  EXPECT_GT(cluster_links, 0u);
  std::printf("nodes: %zu then %zu; the second's links at clusters: %zu\n", large.nodes().size(), small.nodes().size(), cluster_links);
  CorrectionBuffers kept;
  double level_large = 0;
  aggregation_correction(large, 0, &level_large, &kept);  // leaves the larger hierarchy's values in them
  EXPECT_GT(level_large, 0.1);
  Hierarchy with_kept = small, with_own = small;
  double level_kept = 0, level_own = 0;
  const double change_kept = aggregation_correction(with_kept, 0, &level_kept, &kept);
  const double change_own = aggregation_correction(with_own, 0, &level_own);
  EXPECT_GT(level_own, 0.1);  // the correction did something to compare
  EXPECT_EQ(change_kept, change_own);
  EXPECT_EQ(level_kept, level_own);
  for (size_t k = 0; k < small.nodes().size(); ++k) {
    EXPECT_TRUE(same_bits(with_kept[uint32_t(k)].B, with_own[uint32_t(k)].B)) << "node " << k;
    EXPECT_TRUE(same_bits(with_kept[uint32_t(k)].Bt, with_own[uint32_t(k)].Bt)) << "node " << k;
  }
}

}  // namespace
}  // namespace walkrad
