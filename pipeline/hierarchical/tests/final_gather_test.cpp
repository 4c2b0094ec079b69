// The final gather's direct light (final_gather.h) against exact answers: a square emitter over a
// floor, a plate half-way that casts a shadow. In full view the gather is the contour formula itself;
// in the umbra it is 0; in the penumbra the kernel-weighted fraction of the emitter's points seen
// must give the contour formula of the part of the emitter that the point sees.
#include <gtest/gtest.h>

#include "walkrad/formfactor/form_factor.h"
#include "walkrad/hierarchical/final_gather.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

using test::quad;

constexpr double kEmission = 2.0;

// Floor y = 0 (up), emitter 0.5 × 0.5 at y = 1 (down) over the origin, a plate at y = 0.5 from
// x = −0.1 to 1 across the whole depth (facing up).
Scene shadow_scene() {
  Scene s;
  s.source = "final gather test";
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {0, 0, 0}});
  s.materials.push_back({"lamp", {0, 0, 0}, {kEmission, kEmission, kEmission}});
  s.polygons.push_back(quad({-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, 0));
  s.polygons.push_back(quad({-0.25, 1, -0.25}, {0.25, 1, -0.25}, {0.25, 1, 0.25}, {-0.25, 1, 0.25}, 1));
  s.polygons.push_back(quad({-0.1, 0.5, -1}, {-0.1, 0.5, 1}, {1, 0.5, 1}, {1, 0.5, -1}, 0));
  for (const Polygon& p : s.polygons) EXPECT_GT(dot(polygon_normal(p), Vec3(0, 1, 0)) * (p.material == 1 ? -1 : 1), 0.99);
  return s;
}

class FinalGather : public ::testing::Test {
 protected:
  Scene scene = shadow_scene();
  ClusterTree tree = build_cluster_tree(scene);
  RayScene rays{scene};
  Hierarchy h{scene, tree};
  const Vec3 up{0, 1, 0};
  const Polygon& lamp() const { return scene.polygons[1]; }
  Vec3 direct(const Vec3& x, uint64_t& cast) const {
    const DirectGather g(h, nullptr, &rays);
    return g.at(x, up, Vec3{}, {{0, uint32_t(g.emitter_count())}}, cast);
  }
};

TEST_F(FinalGather, InFullViewIsTheContourFormula) {
  uint64_t cast = 0;
  const Vec3 x(-1.5, 0, 0.3);
  EXPECT_NEAR(direct(x, cast).x, kEmission * point_to_polygon(x, up, lamp()), 1e-12);
  EXPECT_EQ(cast, 20u);  // all 16 first rays and the 4 corners' agree: no second pass
}

TEST_F(FinalGather, InTheUmbraIsZero) {
  uint64_t cast = 0;
  EXPECT_EQ(direct({0.6, 0, 0}, cast).x, 0.0);
  EXPECT_EQ(cast, 20u);
}

TEST_F(FinalGather, InThePenumbraSeesThePartOfTheEmitterInView) {
  // From x = (−0.2, 0, 0) the plate's edge at x = −0.1, half-way up, hides the lamp's half x > 0.
  const Vec3 x(-0.2, 0, 0);
  Polygon seen = lamp();
  for (Vec3& v : seen.v) v.x = std::min(v.x, 0.0);
  const double exact = kEmission * point_to_polygon(x, up, seen);
  uint64_t cast = 0;
  const double gathered = direct(x, cast).x;
  constexpr int m = DirectGather::kVertexPenumbra;
  EXPECT_EQ(cast, uint64_t(16 + 4 + m * m));  // the first 16 (and corners) disagree: m² more
  EXPECT_NEAR(gathered, exact, 0.02 * exact);
  EXPECT_EQ(direct(x, cast).x, gathered);  // the same point draws the same points
}

TEST_F(FinalGather, AThinStripOfTheEmitterIsNotTakenForUmbra) {
  // From x = (0.04, 0, 0) the plate hides all of the lamp but the strip x < −0.24, 1 cm of its 50: the
  // 4 first jittered points of that column all miss it 72% of the time, its corners do not.
  const Vec3 x(0.04, 0, 0);
  Polygon seen = lamp();
  for (Vec3& v : seen.v) v.x = std::min(v.x, -0.24);
  const double exact = kEmission * point_to_polygon(x, up, seen);
  uint64_t cast = 0;
  const double gathered = direct(x, cast).x;
  constexpr int m = DirectGather::kVertexPenumbra;
  EXPECT_EQ(cast, uint64_t(16 + 4 + m * m));
  EXPECT_NEAR(gathered, exact, 0.3 * exact);  // 32 rows, each a 0.64 chance of a point in the strip
  // The adaptive mesh's test points do without the corners.
  cast = 0;
  const DirectGather g(h, nullptr, &rays);
  g.at(x, up, Vec3{}, {{0, 1}}, cast, DirectGather::kTestPenumbra);
  EXPECT_TRUE(cast == 16u || cast == uint64_t(16 + DirectGather::kTestPenumbra * DirectGather::kTestPenumbra)) << cast;
}

TEST_F(FinalGather, TakesTheEmittersTheLinksReach) {
  HierarchicalSettings s;
  HierarchicalStats stats;
  solve_hierarchical(h, rays, s, stats);
  const DirectGather g(h, nullptr, &rays);
  ASSERT_EQ(g.emitter_count(), 1u);
  // A floor leaf in full view of the lamp: its links reach the lamp.
  const Vec3 x(-1.5, 0, 0.3);
  const uint32_t leaf = leaf_at(h, h.polygon_root(0), x);
  EXPECT_EQ(g.candidates(leaf), (EmitterRanges{{0, 1}}));
  uint64_t cast = 0;
  EXPECT_EQ(g.at(x, up, Vec3{}, {}, cast).x, 0.0);  // none asked for, none gathered
  EXPECT_EQ(cast, 0u);
}

TEST(FinalGatherBounds, TheFaintestEmittersAreLeftOutWithinWhatIsNegligible) {
  // Two lamps over a floor point: one 1 m above, one 20 m away along the floor's plane and 1 m up. What
  // each could give is ρ E F by the contour formula; left out while their sum stays within `negligible`.
  Scene s;
  s.source = "two lamps";
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {0, 0, 0}});
  s.materials.push_back({"lamp", {0, 0, 0}, {kEmission, kEmission, kEmission}});
  s.polygons.push_back(quad({-2, 0, -2}, {-2, 0, 22}, {2, 0, 22}, {2, 0, -2}, 0));
  s.polygons.push_back(quad({-0.25, 1, -0.25}, {0.25, 1, -0.25}, {0.25, 1, 0.25}, {-0.25, 1, 0.25}, 1));
  s.polygons.push_back(quad({-0.25, 1, 19.75}, {0.25, 1, 19.75}, {0.25, 1, 20.25}, {-0.25, 1, 20.25}, 1));
  const ClusterTree tree = build_cluster_tree(s);
  const RayScene rays(s);
  const Hierarchy h(s, tree);
  const DirectGather g(h, nullptr, &rays);
  ASSERT_EQ(g.emitter_count(), 2u);
  const Vec3 x(0, 0, 0), up(0, 1, 0), rho(0.5, 0.5, 0.5);
  const double near = 0.5 * kEmission * point_to_polygon(x, up, s.polygons[1]);
  const double far = 0.5 * kEmission * point_to_polygon(x, up, s.polygons[2]);
  ASSERT_GT(near, 1000 * far);
  const auto bounds = g.bounds({{0, 2}}, &x, 1, up, rho);
  ASSERT_EQ(bounds.size(), 2u);
  EXPECT_NEAR(bounds[0].first, far, 1e-12 * near);  // ascending
  EXPECT_NEAR(bounds[1].first, near, 1e-12 * near);
  const uint32_t near_index = bounds[1].second;
  EXPECT_EQ(g.strongest({{0, 2}}, &x, 1, up, rho, 0.0), (EmitterRanges{{0, 2}}));
  EXPECT_EQ(g.strongest({{0, 2}}, &x, 1, up, rho, far), (EmitterRanges{{near_index, near_index + 1}}));
  EXPECT_EQ(g.strongest({{0, 2}}, &x, 1, up, rho, near + far), EmitterRanges{});
}

TEST(EmitterRanges, MergeSortedAndDisjoint) {
  EmitterRanges a = {{0, 2}, {5, 7}};
  merge_ranges(a, {{1, 3}, {7, 9}, {12, 13}});
  EXPECT_EQ(a, (EmitterRanges{{0, 3}, {5, 9}, {12, 13}}));
}

}  // namespace
}  // namespace walkrad
