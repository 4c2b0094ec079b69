// Form factors against exact values (Howell's catalogue) and their laws: reciprocity, conservation.
#include "walkrad/formfactor/form_factor.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/classic/form_factor_matrix.h"
#include "walkrad/core/sampling.h"
#include "walkrad/classic/subdivision.h"

namespace walkrad {
namespace {

using test::quad;

// The contour formula's edge angle against libm's atan2 over 16 decades of s/c, both signs of c, at
// every reduction branch's boundary: within 4.5e-16 relative (two ulps; Cephes' atan is one).
TEST(FormFactor, VectorAngleAgreesWithAtan2) {
  double worst = 0;
  const auto check = [&](double s, double c) {
    const double want = std::atan2(s, c), got = vector_angle(s, c);
    worst = std::max(worst, want > 0 ? std::fabs(got - want) / want : std::fabs(got));
  };
  for (int k = 0; k <= 16000; ++k) {
    const double t = std::pow(10.0, -8.0 + k * 1e-3);
    check(t, 1.0);
    check(t, -1.0);
    check(1.0, t);
    check(1.0, -t);
  }
  for (double t : {0.66, 2.414213562373095, 1.0})
    for (double c : {1.0, -1.0})
      for (double d : {-1e-12, 0.0, 1e-12}) check(t * (1 + d), c);
  check(1.0, 0.0);
  check(0.0, 1.0);
  check(0.0, -1.0);
  EXPECT_LT(worst, 4.5e-16);
  EXPECT_EQ(vector_angle(0.0, 0.0), 0.0);
  EXPECT_EQ(vector_angle(2.0, 0.0), std::atan2(2.0, 0.0));
}

// Two coaxial parallel unit squares at distance 1, facing each other: F = 0.19982 (Howell C-11).
TEST(FormFactor, ParallelCoaxialUnitSquares) {
  const Polygon bottom = quad({0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1});  // normal −y... flipped below
  const Polygon lower = quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});   // normal +y
  const Polygon upper = quad({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1});   // normal −y
  EXPECT_NEAR(element_to_element(lower, upper), 0.19982, 1e-3);
  EXPECT_NEAR(element_to_element(upper, lower), 0.19982, 1e-3);
  // A receiver facing away sees nothing.
  EXPECT_EQ(element_to_element(bottom, upper), 0.0);
}

// Two unit squares at right angles sharing an edge: F = 0.20004 (Howell C-14).
TEST(FormFactor, PerpendicularSquaresSharingAnEdge) {
  const Polygon floor = quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});  // normal +y
  const Polygon wall = quad({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1});   // x = 0, normal +x
  EXPECT_NEAR(element_to_element(floor, wall), 0.20004, 1e-3);
  EXPECT_NEAR(element_to_element(wall, floor), 0.20004, 1e-3);
}

TEST(FormFactor, PointToPolygonIsIndependentOfWinding) {
  const Polygon ccw = quad({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1});
  const Polygon cw = quad({0, 1, 1}, {1, 1, 1}, {1, 1, 0}, {0, 1, 0});
  const Vec3 p(0.3, 0, 0.6), n(0, 1, 0);
  EXPECT_GT(point_to_polygon(p, n, ccw), 0.1);
  EXPECT_DOUBLE_EQ(point_to_polygon(p, n, ccw), point_to_polygon(p, n, cw));
}

TEST(FormFactor, PointOnTheSourcePlaneGetsZeroNotNaN) {
  const Polygon src = quad({0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1});
  for (const Vec3 p : {Vec3(2, 0, 0.5), Vec3(0.5, 0, 0.5), Vec3(1, 0, 0.5), Vec3(1, 0, 1)}) {
    const double f = point_to_polygon(p, {0, 1, 0}, src);
    EXPECT_FALSE(std::isnan(f));
    EXPECT_EQ(f, 0.0);
  }
}

// A polygon straddling the receiver's horizon: only the part above counts (clipping), and the
// result stays between the part above alone and the whole hemisphere.
TEST(FormFactor, ClipsToTheReceiversHemisphere) {
  const Polygon straddling = quad({-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1});  // plane z = 1
  const Polygon upper_half = quad({-1, 0, 1}, {1, 0, 1}, {1, 1, 1}, {-1, 1, 1});
  const Vec3 p(0, 0, 0), n(0, 1, 0);  // receiver plane y = 0 cuts the square in half
  EXPECT_NEAR(point_to_polygon(p, n, straddling), point_to_polygon(p, n, upper_half), 1e-12);
}

// Reciprocity A_i F_ij = A_j F_ji for random pairs of small quads facing each other.
TEST(FormFactor, ReciprocityOfRandomPairs) {
  Rng rng(42);
  auto random_quad = [&](double y, bool up) {
    const double x = rng.uniform() * 2, z = rng.uniform() * 2, w = 0.2 + rng.uniform(), d = 0.2 + rng.uniform();
    return up ? quad({x, y, z}, {x, y, z + d}, {x + w, y, z + d}, {x + w, y, z})
              : quad({x, y, z}, {x + w, y, z}, {x + w, y, z + d}, {x, y, z + d});
  };
  for (int k = 0; k < 50; ++k) {
    const Polygon a = random_quad(0, true), b = random_quad(0.3 + 2 * rng.uniform(), false);
    const double ab = polygon_area(a) * element_to_element(a, b), ba = polygon_area(b) * element_to_element(b, a);
    EXPECT_NEAR(ab, ba, 1e-3 * std::max(ab, ba)) << "pair " << k;
  }
}

// Conservation: in a closed, subdivided cube every row of the form factor matrix sums to 1.
TEST(FormFactor, RowsOfAClosedCubeSumToOne) {
  const Scene box = test::closed_box(1.0, {0.5, 0.5, 0.5}, {1, 1, 1});
  const Subdivision sub = subdivide_uniform(box, 0.25);
  ASSERT_EQ(sub.elements.size(), 96u);
  FormFactorCounts counts;
  const FormFactorMatrix f = compute_form_factors(sub, nullptr, nullptr, {}, counts);
  double worst = 0;
  for (size_t i = 0; i < f.rows(); ++i) worst = std::max(worst, std::fabs(f.row_sum(i) - 1.0));
  EXPECT_LT(worst, 1e-3);
  EXPECT_EQ(counts.rays, 0u);
}

}  // namespace
}  // namespace walkrad
