// The contour formula's shortcuts give the plain formula's bits: point_to_polygon (which skips the
// clip where the polygon lies above the horizon) against the clipped edge-by-edge sum written out
// here, and element_to_element with prepared ends and a receiver's points kept across sources (a
// cluster pair's exact form factor) against the same pair from scratch. A bake's determinism and its
// golden files rest on these being equal, not close.
#include "walkrad/formfactor/form_factor.h"

#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "walkrad/core/rounding.h"
#include "walkrad/core/sampling.h"

namespace walkrad {
namespace {

// point_to_polygon written out plainly: always clipped, one edge at a time, in order.
double edge_by_edge(const Vec3& p, const Vec3& n, const Polygon& poly) {
  const Vec3 area_normal = polygon_area_normal(poly);
  const double norm = length(area_normal);
  if (std::fabs(dot(p - poly.v[0], area_normal)) <= norm * (1e-12 * std::sqrt(norm) + rounding_at(p))) return 0.0;
  const ClippedPolygon v = clip_to_hemisphere(p, n, poly.v.data(), poly.count);
  if (v.count < 3) return 0.0;
  double sum = 0.0;
  for (int k = 0; k < v.count; ++k) {
    const Vec3 r0 = v.v[size_t(k)] - p, r1 = v.v[size_t((k + 1) % v.count)] - p;
    const Vec3 c = cross(r0, r1);
    const double cl = length(c);
    if (cl <= 0) continue;
    sum += vector_angle(cl, dot(r0, r1)) * dot(n, c) / cl;
  }
  return std::fabs(sum) / (2.0 * kPi);
}

// element_to_element as it was written before its ends were prepared: everything from the two polygons.
double pair_from_scratch(const Polygon& receiver, const Polygon& source) {
  const Vec3 n = polygon_normal(receiver);
  const double area = polygon_area(receiver);
  if (area <= 0) return 0.0;
  const Vec3 sn = polygon_normal(source);
  const double distance = length(polygon_centroid(receiver) - polygon_centroid(source));
  const int order = quadrature_order(distance, std::sqrt(area), std::sqrt(polygon_area(source)));
  double sum = 0.0;
  for (const QuadraturePoint& q : quadrature_points(receiver, order)) {
    if (dot(q.position - source.v[0], sn) <= 0) continue;
    sum += q.weight * edge_by_edge(q.position, n, source);
  }
  return sum / area;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

Polygon random_polygon(Rng& rng, bool triangle) {
  Polygon p;
  p.count = triangle ? 3 : 4;
  const Vec3 o{rng.uniform() * 4 - 2, rng.uniform() * 4 - 2, rng.uniform() * 4 - 2};
  const Vec3 a{rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5};
  const Vec3 b{rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5};
  p.v[0] = o;
  p.v[1] = o + a;
  p.v[2] = o + a + b;
  p.v[3] = o + b;
  return p;
}

// Random polygons and points, with the cases the branches split on: points on a corner's line
// (an edge with no angle), polygons clipped by the horizon into 3, 4 or 5 corners, polygons wholly
// above it, points on the plane, and every reduction branch of the angle.
TEST(ContourBits, PointToPolygonGivesTheEdgeByEdgeSum) {
  Rng rng(7, 11);
  int compared = 0, clipped = 0, zero = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const Polygon poly = random_polygon(rng, trial % 3 == 0);
    Vec3 p{rng.uniform() * 6 - 3, rng.uniform() * 6 - 3, rng.uniform() * 6 - 3};
    if (trial % 17 == 0) p = poly.v[1] + (poly.v[1] - poly.v[0]) * rng.uniform();  // on an edge's line
    if (trial % 29 == 0) p = sample_polygon(poly, rng.uniform(), rng.uniform());   // on the plane
    const Vec3 n = normalize(Vec3{rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5});
    const double want = edge_by_edge(p, n, poly), got = point_to_polygon(p, n, poly);
    ASSERT_TRUE(same_bits(want, got)) << "trial " << trial << ": " << want << " against " << got;
    ++compared;
    clipped += clip_to_hemisphere(p, n, poly.v.data(), poly.count).count != poly.count;
    zero += want == 0.0;
  }
  EXPECT_GT(clipped, 10000) << "the horizon's clipping went untested";
  EXPECT_GT(zero, 1000) << "the zero cases went untested";
  RecordProperty("compared", compared);
}

TEST(ContourBits, PreparedElementsGiveThePairsOwnBits) {
  Rng rng(3, 5);
  for (int trial = 0; trial < 2000; ++trial) {
    const Polygon receiver = random_polygon(rng, trial % 2 == 0);
    const ElementEnd r(receiver);
    ReceiverPoints points(receiver);  // kept across the sources, as exact_unoccluded keeps it
    for (int s = 0; s < 6; ++s) {
      Polygon source = random_polygon(rng, s % 2 == 1);
      if (s == 5) source = receiver;  // touching itself: the highest order
      const double want = pair_from_scratch(receiver, source);
      const double got = element_to_element(r, ElementEnd(source), points);
      ASSERT_TRUE(same_bits(want, got)) << "trial " << trial << " source " << s;
      ASSERT_TRUE(same_bits(want, element_to_element(receiver, source))) << "trial " << trial << " source " << s;
    }
  }
}

}  // namespace
}  // namespace walkrad
