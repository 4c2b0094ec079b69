// Where refinement ends and how long it has left: the progress line's time left, and diminishing returns
// (refinement_stalled), on the rounds two bakes printed and in the solver itself.
#include <cstddef>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/core/progress.h"
#include "walkrad/formats/scene_reader.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {
namespace {

const std::string kCornell = std::string(WALKRAD_SOURCE_DIR) + "/examples/cornell-box/cornell-box.gltf";

// The progress line's estimate: halving waves leave as many links as the last round added.
TEST(RefinementProgress, EstimatesTimeLeftFromTheShrinkingWave) {
  EXPECT_NEAR(refinement_seconds_left(100, 50, 2.0), 2.0, 1e-12);
  EXPECT_NEAR(refinement_seconds_left(100, 10, 9.0), 1.0, 1e-12);
  EXPECT_LT(refinement_seconds_left(50, 100, 2.0), 0.0);  // still growing: unknown
  EXPECT_EQ(refinement_seconds_left(100, 0, 2.0), 0.0);   // nothing added: done
}

// While the wave still grows, the bound: the memory cap, reached at the solve's rate of growth so far.
TEST(RefinementProgress, BoundsTimeLeftByTheMemoryCapWhileTheWaveGrows) {
  EXPECT_NEAR(seconds_to_memory_cap(14000, 400, 500, 10.0), 1350.0, 1e-9);  // 13,500 MiB at 10 MiB/s
  EXPECT_LT(seconds_to_memory_cap(0, 400, 500, 10.0), 0.0);                 // no cap: unknown
  EXPECT_LT(seconds_to_memory_cap(14000, 500, 500, 10.0), 0.0);             // no growth yet: unknown
  EXPECT_EQ(seconds_to_memory_cap(14000, 400, 14500, 10.0), 0.0);           // past it: the next check stops the bake
}

// Diminishing returns end refinement: the rounds (links, estimated error) of two bakes as their
// progress printed them. RenderPark's office1 doubled its links from round 5 to 7 for 14% less error;
// the Cornell box's last rounds add a few per cent of links each, whatever the error does.
TEST(RefinementProgress, StallsWhereDoublingTheLinksNoLongerLowersTheError) {
  auto rounds = [](std::initializer_list<std::pair<uint64_t, double>> list) {
    std::vector<IterationStats> out;
    for (const auto& [links, error] : list) {
      IterationStats is;
      is.links = links;
      is.estimated_error = error;
      out.push_back(is);
    }
    return out;
  };
  const std::vector<IterationStats> office1 = rounds({{743354, 0.2357}, {2945046, 0.0824}, {7857515, 9.8982},
                                                      {10855184, 0.0376}, {14746269, 0.0345}, {20100710, 0.0310},
                                                      {30617881, 0.0298}});
  std::vector<bool> stalled;
  for (size_t k = 1; k < office1.size(); ++k)
    stalled.push_back(refinement_stalled({office1.begin(), office1.begin() + std::ptrdiff_t(k)}, office1[k]));
  // Round 3's estimate rose (a transient of its two sweeps): no reason; rounds 4 to 6 bought 18% for 1.85×,
  // rounds 5 to 7 14% for 2.08×.
  EXPECT_EQ(stalled, (std::vector<bool>{false, false, false, false, false, true}));

  const std::vector<IterationStats> cornell = rounds({{456, 0.2148}, {83785, 0.0081}, {113732, 0.0026},
                                                      {130999, 0.0028}, {145421, 0.0018}, {150669, 0.0018}});
  for (size_t k = 1; k < cornell.size(); ++k)
    EXPECT_FALSE(refinement_stalled({cornell.begin(), cornell.begin() + std::ptrdiff_t(k)}, cornell[k])) << "round " << k + 1;
  // Without an estimate, nothing stalls.
  std::vector<IterationStats> unmeasured = office1;
  for (IterationStats& is : unmeasured) is.estimated_error = -1;
  EXPECT_FALSE(refinement_stalled({unmeasured.begin(), unmeasured.end() - 1}, unmeasured.back()));
}

// Where links stop buying accuracy the refinement ends (refinement_stalled): the Cornell box with an
// estimate that never falls, as a scene whose extra links only add cost would show it, asked from its
// first round (by default only past a million links, which it never reaches: no round estimated, none
// stalled). Once a round has twice the links of the round two before it, the next round refines
// nothing, sweeps to the tolerance, and the solve ends converged with fewer links than refinement to
// the tolerance makes.
TEST(Hierarchical, RefinementEndsWhereLinksStopLoweringTheEstimate) {
  const Scene scene = read_scene(kCornell);
  const ClusterTree tree = build_cluster_tree(scene);
  const RayScene rays(scene);
  HierarchicalStats full, stalled;
  HierarchicalSettings s;
  s.estimate = [] { return 0.05; };
  {
    Hierarchy h(scene, tree);
    solve_hierarchical(h, rays, s, full);
  }
  EXPECT_EQ(full.stalled_round, -1) << "no estimate, no stall";
  for (const IterationStats& is : full.iterations) EXPECT_EQ(is.estimated_error, -1.0);
  Hierarchy h(scene, tree);
  s.estimate_from_links = 0;
  solve_hierarchical(h, rays, s, stalled);
  ASSERT_GE(stalled.stalled_round, 2);
  const auto k = size_t(stalled.stalled_round);
  // The rounds after it sweep to the tolerance (and confirm, as any settled solve does) adding nothing.
  ASSERT_GE(stalled.iterations.size(), k + 2);
  EXPECT_LE(stalled.iterations.size(), k + 3);
  EXPECT_GE(stalled.iterations[k].links, 2 * stalled.iterations[k - 2].links);
  for (size_t r = k + 1; r < stalled.iterations.size(); ++r) {
    EXPECT_EQ(stalled.iterations[r].new_links, 0u);
    EXPECT_EQ(stalled.iterations[r].elements, stalled.iterations[k].elements);
  }
  EXPECT_TRUE(stalled.converged);
  EXPECT_LT(stalled.links, full.links);
  for (const IterationStats& is : stalled.iterations) EXPECT_EQ(is.estimated_error, 0.05);
}

}  // namespace
}  // namespace walkrad
