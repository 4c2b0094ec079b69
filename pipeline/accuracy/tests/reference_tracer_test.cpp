// The independent reference (reference_tracer.h) against exact answers: the furnace (a closed box,
// every face emitting E and reflecting ρ: B = E / (1 − ρ)) and the direct light from a square emitter
// onto a point below it (ρ E F, F the point-to-parallel-rectangle form factor), each within the
// estimate's own 99.9% confidence interval; and the same estimates whatever the thread count.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/accuracy/reference_tracer.h"

namespace walkrad {
namespace {

// 3.29 σ: a correct estimator fails one check in a thousand; the checks below are a few dozen.
constexpr double kSigmas = 3.29;

// One sample point at each polygon's centroid.
std::vector<SurfacePoint> centroids(const Scene& s) {
  std::vector<SurfacePoint> points;
  for (uint32_t p = 0; p < s.polygons.size(); ++p) points.push_back({p, polygon_centroid(s.polygons[p])});
  return points;
}

class ReferenceFurnace : public ::testing::TestWithParam<double> {};

TEST_P(ReferenceFurnace, AgreesWithEOverOneMinusRhoWithinItsInterval) {
  const double rho = GetParam();
  const Vec3 e(1.0, 2.0, 0.5);
  const Scene box = test::closed_box(2.0, {rho, rho, rho}, e);
  const RayScene rays(box);
  const ReferenceTracer tracer(box, rays);
  std::vector<SurfacePoint> points;
  for (uint32_t p = 0; p < box.polygons.size(); ++p) {
    points.push_back({p, polygon_centroid(box.polygons[p])});
    points.push_back({p, sample_polygon(box.polygons[p], 0.05, 0.9)});  // near an edge
  }
  ReferenceSettings s;
  s.samples = 4096;
  uint64_t cast = 0;
  const std::vector<RadiosityEstimate> est = tracer.estimate(points, s, cast);
  EXPECT_GT(cast, points.size() * size_t(s.samples));
  const Vec3 exact = e / (1.0 - rho);
  for (size_t k = 0; k < est.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(est[k].standard_error[c], 0.0);
      EXPECT_LT(est[k].standard_error[c], 0.02 * exact[c]) << "the interval is too wide to test anything";
      EXPECT_NEAR(est[k].B[c], exact[c], kSigmas * est[k].standard_error[c]) << "point " << k << " channel " << c;
    }
}

INSTANTIATE_TEST_SUITE_P(Reflectances, ReferenceFurnace, ::testing::Values(0.5, 0.8));

// The furnace with walls that also transmit (τ = 0.3): what they pass outwards meets nothing and never
// comes back, and what leaves them inwards is still E + ρ × the inside's uniform irradiance, so B =
// E / (1 − ρ) whatever τ. This holds the reflected branch's reweighting by its probability (ρ chosen
// with probability ρ / (ρ + τ)) and that the outer side brings nothing; what transmission brings from
// the other side has no exact case here (the lamp room's sweep measures it).
TEST(ReferenceFurnace, TransmittingWallsKeepEOverOneMinusRho) {
  const double rho = 0.5;
  const Vec3 e(1.0, 2.0, 0.5);
  Scene box = test::closed_box(2.0, {rho, rho, rho}, e);
  box.materials[0].transmittance = {0.3, 0.3, 0.3};
  const RayScene rays(box);
  const ReferenceTracer tracer(box, rays);
  ReferenceSettings s;
  s.samples = 8192;
  uint64_t cast = 0;
  const std::vector<RadiosityEstimate> est = tracer.estimate(centroids(box), s, cast);
  for (size_t k = 0; k < est.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const double exact = e[c] / (1.0 - rho);
      EXPECT_LT(est[k].standard_error[c], 0.03 * exact);
      EXPECT_NEAR(est[k].B[c], exact, kSigmas * est[k].standard_error[c]) << "point " << k << " channel " << c;
    }
}

// Two furnaces side by side whose shared wall is two coincident polygons back to back (a building's
// zero-thickness wall): the lit box is still exactly E / (1 − ρ) and the dark one black. Were a ray
// from the lit box to meet the dark box's polygon (a back face, black), the lit box would read low.
TEST(ReferenceFurnace, BackToBackWallsKeepEachBoxExact) {
  const double rho = 0.5;
  const Vec3 e(1.0, 1.0, 1.0);
  Scene s = test::closed_box(1.0, {rho, rho, rho}, e);
  const size_t lit = s.polygons.size();
  s.materials.push_back({"dark", {rho, rho, rho}, {}});
  for (Polygon p : test::closed_box(1.0, {rho, rho, rho}, e).polygons) {
    for (Vec3& v : p.v) v.x += 1.0;  // its x = 0 wall lies on the lit box's x = 1 wall, facing away
    p.material = 1;
    s.polygons.push_back(p);
  }
  const RayScene rays(s);
  const ReferenceTracer tracer(s, rays);
  const std::vector<SurfacePoint> points = centroids(s);
  ReferenceSettings settings;
  settings.samples = 4096;
  uint64_t cast = 0;
  const std::vector<RadiosityEstimate> est = tracer.estimate(points, settings, cast);
  const double exact = e.x / (1.0 - rho);
  for (size_t k = 0; k < est.size(); ++k) {
    if (k < lit) {
      EXPECT_NEAR(est[k].B.x, exact, kSigmas * est[k].standard_error.x + 1e-9) << "lit box, face " << k;
      EXPECT_LT(est[k].standard_error.x, 0.02 * exact);
    } else {
      EXPECT_EQ(est[k].B.x, 0.0) << "dark box, face " << k - lit;
    }
  }
}

// Point-to-rectangle form factor, the point below a corner of an a × b rectangle at height c, parallel
// (Howell's catalogue, B-3): F = 1/2π [A/√(1+A²) atan(B/√(1+A²)) + B/√(1+B²) atan(A/√(1+B²))].
double corner_form_factor(double a, double b, double c) {
  const double A = a / c, B = b / c, sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * kPi);
}

TEST(ReferenceDirect, PointBelowASquareLight) {
  Scene s;
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {}});
  s.materials.push_back({"light", {0, 0, 0}, {10, 10, 10}});
  // Floor at y = 0 facing up; a 1 m square light at y = 1 facing down, centred over the origin.
  s.polygons.push_back(test::quad({-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, 0));
  s.polygons.push_back(test::quad({-0.5, 1, -0.5}, {0.5, 1, -0.5}, {0.5, 1, 0.5}, {-0.5, 1, 0.5}, 1));
  ASSERT_GT(polygon_normal(s.polygons[0]).y, 0);
  ASSERT_LT(polygon_normal(s.polygons[1]).y, 0);
  const RayScene rays(s);
  const ReferenceTracer tracer(s, rays);
  ReferenceSettings settings;
  settings.samples = 8192;
  uint64_t cast = 0;
  const std::vector<SurfacePoint> points = {{0, {0, 0, 0}}, {0, {0.5, 0, 0}}, {0, {1.2, 0, 0.3}}};
  const std::vector<RadiosityEstimate> est = tracer.estimate(points, settings, cast);
  for (size_t k = 0; k < points.size(); ++k) {
    const double x = points[k].position.x, z = points[k].position.z;
    // The light as ± corner rectangles from the point's foot (signed widths add up).
    auto f = [](double u, double v) { return std::copysign(1.0, u) * std::copysign(1.0, v) * corner_form_factor(std::fabs(u), std::fabs(v), 1.0); };
    const double F = f(0.5 - x, 0.5 - z) - f(-0.5 - x, 0.5 - z) - f(0.5 - x, -0.5 - z) + f(-0.5 - x, -0.5 - z);
    const double exact = 0.5 * 10 * F;
    EXPECT_NEAR(est[k].B.x, exact, kSigmas * est[k].standard_error.x) << "point " << k << ", F = " << F;
    EXPECT_LT(est[k].standard_error.x, 0.02 * exact);
  }
}

// Punctual lights over a lone floor (nothing else: every bounce escapes, so the estimate is exact):
// B = ρ I cos θ / r², a spot's KHR_lights_punctual falloff between its cones and nothing outside.
TEST(ReferencePunctual, PointAndSpotLightsOverAFloor) {
  Scene s;
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {}});
  s.polygons.push_back(test::quad({-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, 0));
  ASSERT_GT(polygon_normal(s.polygons[0]).y, 0);
  PunctualLight bulb;
  bulb.position = {0, 2, 0};
  bulb.intensity = {8, 8, 8};
  PunctualLight spot;
  spot.type = PunctualLight::Type::spot;
  spot.position = {10, 2, 0};
  spot.direction = {0, -1, 0};
  spot.intensity = {20, 20, 20};
  spot.inner_cone = 0.3;
  spot.outer_cone = 0.6;
  s.lights = {bulb};
  const RayScene rays(s);
  ReferenceSettings settings;
  settings.samples = 16;
  uint64_t cast = 0;
  {
    const ReferenceTracer tracer(s, rays);
    const std::vector<SurfacePoint> points = {{0, {0, 0, 0}}, {0, {1.5, 0, -1}}};
    const std::vector<RadiosityEstimate> est = tracer.estimate(points, settings, cast);
    for (size_t k = 0; k < points.size(); ++k) {
      const Vec3 d = bulb.position - points[k].position;
      const double r2 = dot(d, d);
      EXPECT_NEAR(est[k].B.x, 0.5 * 8 * (d.y / std::sqrt(r2)) / r2, 1e-12) << "point " << k;
    }
  }
  s.lights = {spot};
  const ReferenceTracer tracer(s, rays);
  // On the axis (full), at 0.45 rad off it (between the cones: a quarter-way ramp, squared), at 0.7 (dark).
  for (const double angle : {0.0, 0.45, 0.7}) {
    const Vec3 x(10 + 2 * std::tan(angle), 0, 0);
    const std::vector<RadiosityEstimate> est = tracer.estimate(std::vector<SurfacePoint>{{0, x}}, settings, cast);
    const double c = std::cos(angle), r2 = 4 + 4 * std::tan(angle) * std::tan(angle);
    const double t = std::clamp((c - std::cos(0.6)) / (std::cos(0.3) - std::cos(0.6)), 0.0, 1.0);
    EXPECT_NEAR(est[0].B.x, 0.5 * 20 * t * t * c / r2, 1e-12) << "at " << angle << " rad";
  }
}

// The sun (a directional light, lux read as W/m²) over the same lone floor at 30° from the zenith:
// B = ρ E⊥ times the disc's mean cosine (within 10⁻⁵ of cos 30° for the 0.53° disc); under a roof
// that covers the point, nothing; at a point whose view of the sun the roof's edge cuts in half, half.
TEST(ReferencePunctual, TheSunOverAFloorAndAtARoofsEdge) {
  Scene s;
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {}});
  s.materials.push_back({"roof", {0, 0, 0}, {}});
  s.polygons.push_back(test::quad({-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, 0));
  s.polygons.push_back(test::quad({5, 3, -5}, {15, 3, -5}, {15, 3, 5}, {5, 3, 5}, 1));  // y = 3, x from 5 to 15
  const double theta = 30 * kPi / 180;
  PunctualLight sun;
  sun.type = PunctualLight::Type::directional;
  sun.direction = {-std::sin(theta), -std::cos(theta), 0};  // from +x, above
  sun.intensity = {100, 100, 100};
  s.lights = {sun};
  const RayScene rays(s);
  const ReferenceTracer tracer(s, rays);
  ReferenceSettings settings;
  settings.samples = 4096;
  uint64_t cast = 0;
  // The roof's edge x = 5 seen from the floor towards the sun: x = 5 − 3 tan 30°.
  const double edge = 5 - 3 * std::tan(theta);
  const std::vector<SurfacePoint> points = {{0, {-5, 0, 0}}, {0, {10, 0, 0}}, {0, {edge, 0, 0}}};
  const std::vector<RadiosityEstimate> est = tracer.estimate(points, settings, cast);
  const double lit = 0.5 * 100 * std::cos(theta);
  EXPECT_NEAR(est[0].B.x, lit, 1e-4 * lit);
  EXPECT_EQ(est[1].B.x, 0.0);
  EXPECT_NEAR(est[2].B.x, lit / 2, 0.05 * lit);  // 4,096 draws: σ = 0.8% of lit
}

TEST(ReferenceTracer, SameEstimatesWithOneAndTwoThreads) {
  const Scene box = test::closed_box(1.0, {0.7, 0.6, 0.5}, {1, 1, 1});
  const RayScene rays(box);
  const ReferenceTracer tracer(box, rays);
  const std::vector<SurfacePoint> points = centroids(box);
  ReferenceSettings s;
  s.samples = 64;
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    uint64_t cast = 0;
    return tracer.estimate(points, s, cast);
  };
  const auto a = run(1), b = run(2);
  for (size_t k = 0; k < points.size(); ++k) {
    EXPECT_EQ(a[k].B, b[k].B);
    EXPECT_EQ(a[k].standard_error, b[k].standard_error);
  }
}

}  // namespace
}  // namespace walkrad
