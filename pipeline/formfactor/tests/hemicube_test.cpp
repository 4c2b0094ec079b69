// The hemicube against the exact contour formula for points, the exact polygon-to-polygon form
// factor for polygons, a closed box (the form factors sum to 1), a shadow of known size, and
// polygons that reach behind the point (near-plane clipping).
#include "walkrad/formfactor/hemicube.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "walkrad/testing/howell_catalogue.h"
#include "walkrad/formfactor/form_factor.h"
#include "walkrad/formfactor/form_factor_exact.h"

namespace walkrad {
namespace {

using test::quad;
using test::str;

Polygon reversed(Polygon p) {
  std::reverse(p.v.begin(), p.v.begin() + p.count);
  return p;
}

struct Pair {
  const char* name;
  Polygon receiver, source;
};

std::vector<Pair> catalogue_pairs() {
  const auto par = test::parallel_rectangles(1, 1, 1), flat = test::parallel_rectangles(2, 0.5, 0.5);
  const auto perp = test::perpendicular_rectangles(1, 1, 1), tall = test::perpendicular_rectangles(1, 0.5, 2);
  return {{"parallel squares", par.first, par.second},
          {"parallel 2×0.5 at 0.5", flat.first, flat.second},
          {"perpendicular squares", perp.first, perp.second},
          {"perpendicular 0.5 to 2", tall.first, tall.second}};
}

// From points of the receiver: the error is aliasing at the source's edges, O(1/R).
TEST(Hemicube, PointFormFactorsMatchTheContourFormula) {
  for (const int r : {64, 256}) {
    double worst = 0;
    for (const Pair& pair : catalogue_pairs()) {
      const Vec3 n = polygon_normal(pair.receiver);
      for (const QuadraturePoint& q : quadrature_points(pair.receiver, 4)) {
        const double f = hemicube_form_factors(q.position, n, {pair.source}, r)[0];
        worst = std::max(worst, std::fabs(f - point_to_polygon(q.position, n, pair.source)));
      }
    }
    EXPECT_LT(worst, r == 64 ? 6e-3 : 2e-3) << "R " << r;
    RecordProperty("worst_point_error_R" + std::to_string(r), str(worst));
  }
}

// Integrated over the receiver (8×8 Gauss points), aliasing errors partly cancel.
TEST(Hemicube, PolygonFormFactorsMatchTheExactMethod) {
  const int r = 256;
  for (const Pair& pair : catalogue_pairs()) {
    const Vec3 n = polygon_normal(pair.receiver);
    double sum = 0;
    for (const QuadraturePoint& q : quadrature_points(pair.receiver, 8))
      sum += q.weight * hemicube_form_factors(q.position, n, {pair.source}, r)[0];
    EXPECT_NEAR(sum / polygon_area(pair.receiver), polygon_to_polygon_exact(pair.receiver, pair.source), 1e-3)
        << pair.name;
  }
}

// Inside a closed box every direction ends on a wall: the form factors sum to 1, less the delta
// form factors' own discretisation error, O(1/R²).
TEST(Hemicube, FormFactorsInAClosedBoxSumToOne) {
  const Scene box = test::closed_box(1.0, {0.5, 0.5, 0.5}, {1, 1, 1});
  for (const Vec3& p : {Vec3(0.3, 0.0, 0.6), Vec3(0.5, 0.5, 0.5), Vec3(0.01, 0.0, 0.99)}) {
    const std::vector<double> f = hemicube_form_factors(p, {0, 1, 0}, box.polygons, 256);
    double sum = 0;
    for (double v : f) sum += v;
    EXPECT_NEAR(sum, 1.0, 1e-4) << p.x << ", " << p.y << ", " << p.z;
  }
}

// Polygons that cross the receiver's plane or pass behind the point: clipped to each face's frustum
// (near plane included), they match the contour formula, which clips to the hemisphere.
TEST(Hemicube, PolygonsReachingBehindThePointAreClipped) {
  const Vec3 p(0, 0, 0), n(0, 1, 0);
  const std::vector<Polygon> sources = {
      quad({-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}),          // straddles the horizon, facing −z
      quad({-3, 1, -3}, {3, 1, -3}, {3, 1, 3}, {-3, 1, 3}),          // a ceiling over every side face
      quad({0.5, -2, -4}, {0.5, -2, 4}, {0.5, 3, 4}, {0.5, 3, -4}),  // a wall, from below to behind
  };
  for (const Polygon& source : sources) {
    const Polygon front = dot(p - source.v[0], polygon_normal(source)) > 0 ? source : reversed(source);
    EXPECT_NEAR(hemicube_form_factors(p, n, {front}, 256)[0], point_to_polygon(p, n, front), 2e-3);
  }
}

// A plate between a point and a parallel square hides the square's part in the plate's shadow;
// parallel to the point's plane, the shadow subtends the plate's own projected solid angle. The plate
// gets its share only when it faces the point, and occludes either way.
TEST(Hemicube, OccludersCastExactShadowsAndBackFacesGetNothing) {
  const auto [lower, upper] = test::parallel_rectangles(1, 1, 1);
  const Polygon plate_up = quad({0.25, 0.5, 0.25}, {0.25, 0.5, 0.75}, {0.75, 0.5, 0.75}, {0.75, 0.5, 0.25});
  const Polygon plate_down = reversed(plate_up);  // facing −y, towards the points below
  const Vec3 n(0, 1, 0);
  for (const Vec3& p : {Vec3(0.5, 0, 0.5), Vec3(0.3, 0, 0.6), Vec3(0.1, 0, 0.1)}) {
    // Shadow of [0.25, 0.75]² at y = 0.5 on y = 1, from p: scaled by 2 about p, clipped to the square.
    const double x0 = std::max(0.0, 0.5 - p.x), x1 = std::min(1.0, 1.5 - p.x);
    const double z0 = std::max(0.0, 0.5 - p.z), z1 = std::min(1.0, 1.5 - p.z);
    const Polygon shadow = quad({x0, 1, z0}, {x1, 1, z0}, {x1, 1, z1}, {x0, 1, z1});
    const double visible = point_to_polygon(p, n, upper) - point_to_polygon(p, n, shadow);
    const std::vector<double> facing = hemicube_form_factors(p, n, {upper, plate_down}, 256);
    EXPECT_NEAR(facing[0], visible, 2e-3) << p.x << ", " << p.z;
    EXPECT_NEAR(facing[1], point_to_polygon(p, n, plate_down), 2e-3) << p.x << ", " << p.z;
    const std::vector<double> away = hemicube_form_factors(p, n, {upper, plate_up}, 256);
    EXPECT_NEAR(away[0], visible, 2e-3) << p.x << ", " << p.z;
    EXPECT_EQ(away[1], 0.0);
  }
}

// The receiver's own polygon (edge-on) and polygons behind the point get nothing.
TEST(Hemicube, EdgeOnAndBehindPolygonsGetNothing) {
  const auto [lower, upper] = test::parallel_rectangles(1, 1, 1);
  const Polygon below = quad({0, -1, 0}, {0, -1, 1}, {1, -1, 1}, {1, -1, 0});  // y = −1, facing +y
  const std::vector<double> f = hemicube_form_factors({0.5, 0, 0.5}, {0, 1, 0}, {lower, upper, below}, 64);
  EXPECT_EQ(f[0], 0.0);
  EXPECT_GT(f[1], 0.2);
  EXPECT_EQ(f[2], 0.0);
}

}  // namespace
}  // namespace walkrad
