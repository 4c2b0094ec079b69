// Link evaluation on its own (link_evaluator.h): pending links in, evaluated links out, against
// closed-form form factors (Howell's catalogue), reciprocity, a proven occlusion and the same bits
// whatever the thread count.
#include <cstring>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "link_evaluator.h"
#include "polygon_scene.h"
#include "walkrad/testing/howell_catalogue.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad::hierarchical_detail {
namespace {

// A scene of the given polygons (polygon_scene.h) with its evaluator.
struct LinkScene : test::PolygonScene {
  std::unique_ptr<LinkEvaluator> evaluator;

  explicit LinkScene(std::vector<Polygon> polygons)
      : PolygonScene(std::move(polygons)), evaluator(std::make_unique<LinkEvaluator>(*h, *rays, settings)) {}
  // Polygon a's element receiving from polygon b's, evaluated.
  Pending link(uint32_t a, uint32_t b, bool cast, int samples = 64) const {
    Pending p(LinkRequest{h->polygon_root(a), h->polygon_root(b), samples, cast, false});
    std::vector<RayScene::Segment> segments;
    std::vector<double> visible, weights;
    evaluator->evaluate(p, segments, visible, weights);
    return p;
  }
};

TEST(LinkEvaluator, AnElementLinkGivesTheCatalogueFormFactor) {
  // C-11: parallel, directly opposed squares. Unoccluded, the contour formula is exact to its
  // quadrature, whose order falls with the distance (quadrature_order: 0.49% off at 4 sides apart,
  // where the link's share of the error budget is as small); with rays that all arrive, the control
  // variate adds nothing.
  for (const auto& [c, tolerance] : {std::pair{0.5, 2e-3}, {1.0, 2e-3}, {4.0, 1e-2}}) {
    const test::RectanglePair pair = test::parallel_rectangles(1.0, 1.0, c);
    const LinkScene s({pair.first, pair.second});
    const double expected = test::howell_c11(1.0, 1.0, c);
    const Pending open = s.link(0, 1, false);
    EXPECT_NEAR(open.F, expected, tolerance * expected) << "c = " << c;
    EXPECT_EQ(open.sigma, 0.0f);
    EXPECT_EQ(open.rays, 0u);
    const Pending cast = s.link(0, 1, true);
    EXPECT_EQ(cast.F, open.F) << "rays that all arrive change F";
    EXPECT_GT(cast.rays, 0u);
    EXPECT_FALSE(cast.proven);
    EXPECT_NEAR(cast.open, expected, tolerance * expected);
  }
}

TEST(LinkEvaluator, ElementLinksAreReciprocal) {
  // C-14: a floor and a wall at 90° sharing an edge; A_i F_ij = A_j F_ji, and each the catalogue's.
  const double l = 1.0, w = 1.0, height = 2.0;
  const test::RectanglePair pair = test::perpendicular_rectangles(l, w, height);
  const LinkScene s({pair.first, pair.second});
  const double floor_to_wall = s.link(0, 1, false).F, wall_to_floor = s.link(1, 0, false).F;
  EXPECT_NEAR(floor_to_wall, test::howell_c14(l, w, height), 0.01 * test::howell_c14(l, w, height));
  EXPECT_NEAR(w * l * floor_to_wall, height * l * wall_to_floor, 0.01 * w * l * floor_to_wall);
}

TEST(LinkEvaluator, ALinkThroughAWallIsZeroAndProven) {
  // The squares of C-11 (c = 2) with a wall between them wider than both: every ray is blocked and the
  // wall's plane proves that every other would be (occlusion_proof.h): F = 0 and nothing uncertain.
  const test::RectanglePair pair = test::parallel_rectangles(1.0, 1.0, 2.0);
  const Polygon wall = test::quad({-1, 1, -1}, {2, 1, -1}, {2, 1, 2}, {-1, 1, 2});
  const LinkScene s({pair.first, pair.second, wall});
  const Pending p = s.link(0, 1, true);
  EXPECT_EQ(p.F, 0.0);
  EXPECT_TRUE(p.proven);
  EXPECT_EQ(p.sigma, 0.0f);
  EXPECT_GT(p.open, 0.0f);  // what it would carry unoccluded
}

TEST(LinkEvaluator, AHalfWallHidesAboutHalfWithinItsNoise) {
  // The wall covers half of the space between the squares (x < 0.5): F is the unoccluded factor less
  // what the rays find hidden, an unbiased estimate whose σ the link keeps. By symmetry the hidden part
  // lies between a quarter and three quarters of it.
  const test::RectanglePair pair = test::parallel_rectangles(1.0, 1.0, 2.0);
  const Polygon wall = test::quad({-1, 1, -1}, {0.5, 1, -1}, {0.5, 1, 2}, {-1, 1, 2});
  const LinkScene s({pair.first, pair.second, wall});
  const Pending p = s.link(0, 1, true, 256);
  const double open = test::howell_c11(1.0, 1.0, 2.0);
  EXPECT_GT(p.F, 0.25 * open);
  EXPECT_LT(p.F, 0.75 * open);
  EXPECT_GT(p.sigma, 0.0f);
  EXPECT_LT(p.sigma, 0.2 * open);
  EXPECT_FALSE(p.proven);
  // Link::share: the receiver's children under the open half get more than those under the wall.
  float open_side = 0, shut_side = 0;
  const std::array<Polygon, 4> kids = split_element((*s.h)[s.h->polygon_root(0)].shape);
  for (int c = 0; c < 4; ++c) (polygon_centroid(kids[size_t(c)]).x > 0.5 ? open_side : shut_side) += p.share[size_t(c)];
  EXPECT_GT(open_side, shut_side);
}

TEST(LinkEvaluator, TheSameBitsWhateverTheThreadCount) {
  // Each link draws from its own stream (its two ends): a list evaluated on one thread or two gives
  // the same bits, link by link.
  const test::RectanglePair pair = test::parallel_rectangles(1.0, 1.0, 2.0);
  const Polygon wall = test::quad({-1, 1, -1}, {0.5, 1, -1}, {0.5, 1, 2}, {-1, 1, 2});
  const LinkScene s({pair.first, pair.second, wall});
  auto evaluated = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    PendingList list;
    for (int k = 0; k < 256; ++k)
      list.emplace_back(LinkRequest{s.h->polygon_root(uint32_t(k % 2)), s.h->polygon_root(uint32_t(1 - k % 2)), 16 + k % 7, true, false});
    s.evaluator->evaluate_range(list, 0, list.size());
    return list;
  };
  const PendingList one = evaluated(1), two = evaluated(2);
  ASSERT_EQ(one.size(), two.size());
  for (size_t k = 0; k < one.size(); ++k) EXPECT_EQ(std::memcmp(&one[k], &two[k], sizeof(Pending)), 0) << "link " << k;
}

}  // namespace
}  // namespace walkrad::hierarchical_detail
