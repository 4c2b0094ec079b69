// The exact polygon-to-polygon form factor against Howell's catalogue in closed form, and the laws
// it must keep: reciprocity, additivity, one-sidedness. Also the contour formula for a point
// (point_to_polygon) against a disc, and the quadrature estimate (element_to_element) against both.
#include "walkrad/formfactor/form_factor_exact.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "walkrad/testing/howell_catalogue.h"
#include "walkrad/formfactor/form_factor.h"
#include "walkrad/core/sampling.h"

namespace walkrad {
namespace {

using test::quad;
using test::str;

Polygon triangle(Vec3 a, Vec3 b, Vec3 c) {
  Polygon p;
  p.v = {a, b, c, c};
  p.count = 3;
  return p;
}

Polygon reversed(Polygon p) {
  std::reverse(p.v.begin(), p.v.begin() + p.count);
  return p;
}

Polygon rotated(Polygon p, int by) {
  std::rotate(p.v.begin(), p.v.begin() + by, p.v.begin() + p.count);
  return p;
}

// (a, b, c): rectangle sides and distance, from nearly touching to far apart, square to elongated.
const double kParallel[][3] = {{1, 1, 1},   {1, 1, 0.1}, {1, 1, 0.02}, {1, 1, 10}, {2, 0.5, 1},
                               {3, 1, 0.5}, {0.2, 5, 2}, {1, 4, 0.25}, {0.5, 0.5, 3}};
// (l, w, h): common edge, floor width, wall height.
const double kPerpendicular[][3] = {{1, 1, 1}, {1, 2, 0.5}, {2, 1, 1}, {0.5, 3, 1}, {1, 0.1, 5}, {4, 1, 1}, {1, 0.02, 0.02}};

TEST(ExactFormFactor, CatalogueUnitSquares) {
  const auto par = test::parallel_rectangles(1, 1, 1);
  const auto perp = test::perpendicular_rectangles(1, 1, 1);
  EXPECT_NEAR(polygon_to_polygon_exact(par.first, par.second), 0.19982, 5e-6);
  EXPECT_NEAR(polygon_to_polygon_exact(perp.first, perp.second), 0.20004, 5e-6);
}

TEST(ExactFormFactor, ParallelRectanglesMatchHowellC11) {
  double worst_exact = 0, worst_quadrature = 0;
  for (const auto& c : kParallel) {
    const auto pair = test::parallel_rectangles(c[0], c[1], c[2]);
    const double reference = test::howell_c11(c[0], c[1], c[2]);
    for (const auto& [i, j] : {std::pair(pair.first, pair.second), std::pair(pair.second, pair.first)}) {
      const double exact = polygon_to_polygon_exact(i, j);
      EXPECT_NEAR(exact, reference, 1e-7) << c[0] << "×" << c[1] << " at " << c[2];
      worst_exact = std::max(worst_exact, std::fabs(exact - reference));
      // The cheap quadrature is only expected to hold 1e-3 where the distance is not far below the size.
      if (c[2] >= 0.25 * std::min(c[0], c[1])) {
        const double quadrature = element_to_element(i, j);
        EXPECT_NEAR(quadrature, reference, 1e-3) << c[0] << "×" << c[1] << " at " << c[2];
        worst_quadrature = std::max(worst_quadrature, std::fabs(quadrature - reference));
      }
    }
  }
  RecordProperty("worst_exact_error", str(worst_exact));
  RecordProperty("worst_quadrature_error", str(worst_quadrature));
}

TEST(ExactFormFactor, PerpendicularRectanglesMatchHowellC14) {
  double worst_exact = 0, worst_quadrature = 0;
  for (const auto& c : kPerpendicular) {
    const double l = c[0], w = c[1], h = c[2];
    const auto [floor, wall] = test::perpendicular_rectangles(l, w, h);
    const double floor_to_wall = test::howell_c14(l, w, h), wall_to_floor = test::howell_c14(l, h, w);
    const double exact_fw = polygon_to_polygon_exact(floor, wall), exact_wf = polygon_to_polygon_exact(wall, floor);
    EXPECT_NEAR(exact_fw, floor_to_wall, 1e-7) << l << ", " << w << ", " << h;
    EXPECT_NEAR(exact_wf, wall_to_floor, 1e-7) << l << ", " << w << ", " << h;
    worst_exact = std::max({worst_exact, std::fabs(exact_fw - floor_to_wall), std::fabs(exact_wf - wall_to_floor)});
    // element_to_element's Gauss points cannot resolve the shared edge of a very thin strip.
    if (std::min(w, h) >= 0.1 * l && std::max(w, h) <= 3 * l) {
      const double q_fw = element_to_element(floor, wall), q_wf = element_to_element(wall, floor);
      EXPECT_NEAR(q_fw, floor_to_wall, 1e-3) << l << ", " << w << ", " << h;
      EXPECT_NEAR(q_wf, wall_to_floor, 1e-3) << l << ", " << w << ", " << h;
      worst_quadrature =
          std::max({worst_quadrature, std::fabs(q_fw - floor_to_wall), std::fabs(q_wf - wall_to_floor)});
    }
  }
  RecordProperty("worst_exact_error", str(worst_exact));
  RecordProperty("worst_quadrature_error", str(worst_quadrature));
}

// A differential area on the axis of a disc: the fan of N thin triangles that makes a regular
// N-gon, through point_to_polygon (exact per triangle, additive), against the N-gon's closed form
// and against the disc's r²/(r²+h²). The inscribed N-gon misses a rim sliver of area fraction
// 2π²/(3N²) + O(N⁻⁴), where the kernel is h²/(π(r²+h²)²): the gap to the disc is known to leading order.
TEST(ExactFormFactor, PointToDiscByAFanOfTriangles) {
  const double r = 1.0;
  for (const double h : {0.1, 0.5, 1.0, 3.0}) {
    for (const int n : {64, 128, 256, 512}) {
      const Vec3 p(0, h, 0), normal(0, -1, 0);  // above the disc in y = 0, looking down
      double sum = 0;
      for (int k = 0; k < n; ++k) {
        const double a0 = 2 * kPi * k / n, a1 = 2 * kPi * (k + 1) / n;
        sum += point_to_polygon(p, normal,
                                triangle({0, 0, 0}, {r * std::cos(a0), 0, r * std::sin(a0)},
                                         {r * std::cos(a1), 0, r * std::sin(a1)}));
      }
      EXPECT_NEAR(sum, test::regular_ngon_on_axis(n, r, h), 1e-12) << "h " << h << ", N " << n;
      const double gap = test::disc_on_axis(r, h) - sum;
      const double predicted = 2 * kPi * kPi / (3.0 * n * n) * r * r * h * h / std::pow(r * r + h * h, 2);
      EXPECT_NEAR(gap / predicted, 1.0, 2e-3) << "h " << h << ", N " << n;
    }
  }
}

// The exact method from a tiny receiver on the axis to each fan triangle: additivity over the fan
// and the differential limit (a receiver of size δ differs from a point by O(δ²)).
TEST(ExactFormFactor, TinyReceiverSeesTheFanLikeAPoint) {
  const int n = 32;
  const double h = 0.7, r = 1.0, delta = 1e-3;
  const Polygon receiver = quad({-delta / 2, h, -delta / 2}, {delta / 2, h, -delta / 2}, {delta / 2, h, delta / 2},
                                {-delta / 2, h, delta / 2});  // facing −y
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const double a0 = 2 * kPi * k / n, a1 = 2 * kPi * (k + 1) / n;
    // Counter-clockwise seen from +y: the triangles face the receiver.
    sum += polygon_to_polygon_exact(receiver, triangle({0, 0, 0}, {r * std::cos(a1), 0, r * std::sin(a1)},
                                                       {r * std::cos(a0), 0, r * std::sin(a0)}));
  }
  EXPECT_NEAR(sum, test::regular_ngon_on_axis(n, r, h), 1e-6);
}

// A random convex polygon (triangle, parallelogram or general convex quad) of size about 1 around
// a random centre, in a random plane, with a random winding.
Polygon random_polygon(Rng& rng) {
  const Vec3 centre(4 * rng.uniform() - 2, 4 * rng.uniform() - 2, 4 * rng.uniform() - 2);
  Vec3 n;
  do n = Vec3(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1);
  while (dot(n, n) > 1 || dot(n, n) < 1e-2);
  n = normalize(n);
  const Vec3 t = normalize(cross(n, std::fabs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0))), b = cross(n, t);
  const int count = rng.uniform() < 0.4 ? 3 : 4;
  // Corners at increasing angles on an ellipse: convex, counter-clockwise about n.
  const double ra = 0.3 + rng.uniform(), rb = 0.3 + rng.uniform(), start = 2 * kPi * rng.uniform();
  Polygon p;
  p.count = uint8_t(count);
  for (int k = 0; k < count; ++k) {
    const double angle = start + 2 * kPi * (k + 0.8 * rng.uniform()) / count;
    p.v[k] = centre + t * (ra * std::cos(angle)) + b * (rb * std::sin(angle));
  }
  if (count == 3) p.v[3] = p.v[2];
  return rng.uniform() < 0.5 ? reversed(p) : p;
}

bool entirely_behind(const Polygon& p, const Polygon& plane_of) {
  const Vec3 n = polygon_normal(plane_of);
  for (int k = 0; k < p.count; ++k)
    if (dot(p.v[k] - plane_of.v[0], n) > 1e-9) return false;
  return true;
}

TEST(ExactFormFactor, ReciprocityOfRandomPairs) {
  Rng rng(7);
  int tested = 0;
  double worst = 0;
  while (tested < 200) {
    const Polygon a = random_polygon(rng), b = random_polygon(rng);
    if (entirely_behind(a, b) || entirely_behind(b, a)) continue;
    ++tested;
    const double fab = polygon_to_polygon_exact(a, b), fba = polygon_to_polygon_exact(b, a);
    ASSERT_TRUE(std::isfinite(fab) && std::isfinite(fba));
    EXPECT_GE(fab, 0.0);
    EXPECT_LE(fab, 1.0);
    const double ab = polygon_area(a) * fab, ba = polygon_area(b) * fba;
    const double rel = std::fabs(ab - ba) / std::max({ab, ba, 1e-300});
    if (std::max(ab, ba) > 1e-12) worst = std::max(worst, rel);  // grazing pairs have only absolute digits
    // Relative 1e-6, with a floor for grazing pairs whose A F (~1e-16) is below the edge terms' rounding.
    EXPECT_LE(std::fabs(ab - ba), 1e-6 * std::max(ab, ba) + 1e-15) << "pair " << tested << ": " << ab << " vs " << ba;
  }
  RecordProperty("worst_relative_reciprocity_error", str(worst));
}

// The result depends on which side is the front (the winding), not on where the vertex list starts.
TEST(ExactFormFactor, WindingOnlyChoosesTheFront) {
  const auto [lower, upper] = test::parallel_rectangles(1, 2, 0.7);
  const double f = polygon_to_polygon_exact(lower, upper);
  for (int by = 1; by < 4; ++by) {
    EXPECT_NEAR(polygon_to_polygon_exact(rotated(lower, by), upper), f, 1e-12);
    EXPECT_NEAR(polygon_to_polygon_exact(lower, rotated(upper, by)), f, 1e-12);
  }
  // Turned away from each other, either or both: nothing, and never a negative value.
  EXPECT_EQ(polygon_to_polygon_exact(reversed(lower), upper), 0.0);
  EXPECT_EQ(polygon_to_polygon_exact(lower, reversed(upper)), 0.0);
  EXPECT_EQ(polygon_to_polygon_exact(reversed(lower), reversed(upper)), 0.0);
}

TEST(ExactFormFactor, CoplanarAndDegeneratePairsGiveZeroNotNaN) {
  const Polygon a = quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});
  const Polygon beside = quad({1, 0, 0}, {1, 0, 1}, {2, 0, 1}, {2, 0, 0});
  const Polygon overlapping = quad({0.5, 0, 0.5}, {0.5, 0, 1.5}, {1.5, 0, 1.5}, {1.5, 0, 0.5});
  const Polygon flipped = reversed(overlapping);
  const Polygon degenerate = quad({0, 1, 0}, {1, 1, 0}, {2, 1, 0}, {3, 1, 0});
  for (const Polygon& b : {a, beside, overlapping, flipped, degenerate}) {
    EXPECT_EQ(polygon_to_polygon_exact(a, b), 0.0);
    EXPECT_EQ(polygon_to_polygon_exact(b, a), 0.0);
  }
}

// Only the part of the receiver in front of the source's plane sees it.
TEST(ExactFormFactor, ReceiverStraddlingTheSourcePlaneCountsItsFrontPart) {
  const Polygon source = quad({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1});  // y = 1, facing −y
  const Polygon wall = quad({-0.5, 0, 0}, {-0.5, 2, 0}, {-0.5, 2, 1}, {-0.5, 0, 1});  // x = −0.5, facing +x
  const Polygon lower_half = quad({-0.5, 0, 0}, {-0.5, 1, 0}, {-0.5, 1, 1}, {-0.5, 0, 1});
  const double whole = polygon_area(wall) * polygon_to_polygon_exact(wall, source);
  const double half = polygon_area(lower_half) * polygon_to_polygon_exact(lower_half, source);
  EXPECT_GT(half, 0.01);
  EXPECT_NEAR(whole, half, 1e-9);
  // Entirely behind: nothing.
  const Polygon above = quad({-0.5, 1.5, 0}, {-0.5, 2, 0}, {-0.5, 2, 1}, {-0.5, 1.5, 1});
  EXPECT_EQ(polygon_to_polygon_exact(above, source), 0.0);
}

// Two squares cutting through each other along a line: each sees only the half of the other in
// front of it, which is C-14's pair with a common edge of length 2.
TEST(ExactFormFactor, IntersectingSquaresAreTwoPerpendicularHalves) {
  const Polygon horizontal = quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});  // facing +y
  const Polygon vertical = quad({0, -1, -1}, {0, 1, -1}, {0, 1, 1}, {0, -1, 1});    // facing +x
  const double expected = 0.5 * test::howell_c14(2, 1, 1);  // receiver half of area 2, of 4
  EXPECT_NEAR(polygon_to_polygon_exact(horizontal, vertical), expected, 1e-7);
  EXPECT_NEAR(polygon_to_polygon_exact(vertical, horizontal), expected, 1e-7);
}

// Splitting the source into two triangles splits the form factor, also across a shared edge and
// for polygons touching at a single vertex.
TEST(ExactFormFactor, AdditivityOverASplitSource) {
  const auto [floor, wall] = test::perpendicular_rectangles(1, 1.3, 0.8);
  const Polygon t0 = triangle(wall.v[0], wall.v[1], wall.v[2]), t1 = triangle(wall.v[0], wall.v[2], wall.v[3]);
  EXPECT_NEAR(polygon_to_polygon_exact(floor, wall),
              polygon_to_polygon_exact(floor, t0) + polygon_to_polygon_exact(floor, t1), 1e-8);
  // Touching at the corner (0, 0, 0) only: a wall at z <= 0 beside the floor's edge.
  const Polygon corner_wall = quad({0, 0, 0}, {0, 0, -1}, {0, 1, -1}, {0, 1, 0});  // x = 0, facing +x
  const Polygon c0 = triangle(corner_wall.v[0], corner_wall.v[1], corner_wall.v[2]),
                c1 = triangle(corner_wall.v[0], corner_wall.v[2], corner_wall.v[3]);
  const double whole = polygon_to_polygon_exact(floor, corner_wall);
  EXPECT_GT(whole, 0.0);
  EXPECT_NEAR(whole, polygon_to_polygon_exact(floor, c0) + polygon_to_polygon_exact(floor, c1), 1e-8);
}

// Far apart, the form factor tends to A_j cosθ_i cosθ_j / (π r²): for unit squares at distance d,
// cosθ cosθ' / r² = d² / r⁴ with r² = d² + ρ² and E[ρ²] = 1/3, so F = (1 − 2/(3d²) + O(d⁻⁴)) / (π d²).
// This checks the digits the contour sum keeps when its terms cancel (C-11 itself loses them: at
// c = 1000 its terms cancel to 1e-4 relative).
TEST(ExactFormFactor, DistantSmallPolygonsTendToThePointFormula) {
  for (const double d : {10.0, 100.0, 1000.0, 1e4}) {
    const auto [lower, upper] = test::parallel_rectangles(1, 1, d);
    const double point = 1.0 / (kPi * d * d), exact = polygon_to_polygon_exact(lower, upper);
    EXPECT_NEAR(exact / point, 1 - 2 / (3 * d * d), std::max(5e-8, 1 / (d * d * d * d))) << d;
    if (d <= 100) {
      EXPECT_NEAR(exact, test::howell_c11(1, 1, d), 1e-12) << d;
    }
  }
}

}  // namespace
}  // namespace walkrad
