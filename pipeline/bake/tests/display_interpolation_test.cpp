// What the display shows between vertices, against exact answers (the contour formula), with the
// defaults a user gets: the output mesh is split where Gouraud shading between the vertices' own values
// would depart from the light (display_refinement.h), and the bake's estimate counts what it leaves.
// - A 1 m square 1 m under a 1 m square emitter (ρ 0.5), with and without viewpoints: kept as one
//   element, its corners' light is 31% below the mean ρ F E and 42% below the centre's; split, the
//   displayed mean is within 1% of ρ F E and the centre within 2% of its point value, and the estimate
//   is neither 0 nor more than twice the measured error.
// - A floor lit only by a 1 m² emitter filling a window (every other surface black), two viewpoints on
//   it: every point of the floor within 2% of ρ E F(x → window), where the light is at least a tenth of
//   the floor's brightest, and the estimate within 0.5–2× of the floor's RMS error.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "default_bake.h"
#include "walkrad/formfactor/form_factor.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

using test::rect;
constexpr int X = 0, Y = 1, Z = 2;

// Two directly opposed parallel rectangles a × b, c apart (Howell's catalogue, C-11).
double opposed_rectangles(double a, double b, double c) {
  const double x = a / c, y = b / c, x1 = std::sqrt(1 + x * x), y1 = std::sqrt(1 + y * y);
  return 2 / (kPi * x * y) *
         (std::log(x1 * y1 / std::sqrt(1 + x * x + y * y)) + x * y1 * std::atan(x / y1) + y * x1 * std::atan(y / x1) -
          x * std::atan(x) - y * std::atan(y));
}

double estimated_error(const test::DefaultBake& b) {
  std::ifstream in(b.folder() / "scene.bake" / "report.json");
  return nlohmann::json::parse(in)["solver"]["estimated_error"]["overall"].get<double>();
}

double baked_at(const test::DefaultBake& b, const Vec3& p) {
  const BakeSampler::Sample s = b.sampler.along(p + Vec3(0, 0.05, 0), {0, -1, 0});
  EXPECT_TRUE(s.hit && std::fabs(s.distance - 0.05) < 1e-3);
  return luminance(s.B);
}

class ParallelSquares : public ::testing::TestWithParam<bool> {};

TEST_P(ParallelSquares, TheDisplayedMeanAndCentreAreExact) {
  const bool viewpoint = GetParam();
  Scene s;
  s.source = "parallel squares";
  s.materials.push_back({"receiver", {0.5, 0.5, 0.5}, {0, 0, 0}});
  s.materials.push_back({"emitter", {0, 0, 0}, {kPi, kPi, kPi}});  // radiance 1
  s.polygons.push_back(rect(Y, 0, 0, 1, 0, 1, +1, 0));
  s.polygons.push_back(rect(Y, 1, 0, 1, 0, 1, -1, 1));
  if (viewpoint) s.cameras.push_back({"above", {0.5, 0.5, 0.5}, {0, -1, 0}, {0, 0, 1}, 1.2, 1.0});
  const test::DefaultBake b(viewpoint ? "squares-seen" : "squares", std::move(s));
  const Polygon& emitter = b.scene.polygons[1];
  const double mean_exact = 0.5 * kPi * opposed_rectangles(1, 1, 1);
  // The displayed mean over a grid of cell centres, and the relative RMS against the point values.
  constexpr int kGrid = 64;
  double mean = 0, squares = 0, reference = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const Vec3 p((i + 0.5) / kGrid, 0, (j + 0.5) / kGrid);
      const double shown = baked_at(b, p), exact = 0.5 * kPi * point_to_polygon(p, {0, 1, 0}, emitter);
      mean += shown / (kGrid * kGrid);
      squares += (shown - exact) * (shown - exact);
      reference += exact * exact;
    }
  const double centre = baked_at(b, {0.5, 0, 0.5}), centre_exact = 0.5 * kPi * point_to_polygon({0.5, 0, 0.5}, {0, 1, 0}, emitter);
  const double rms = std::sqrt(squares / reference), estimate = estimated_error(b);
  std::printf("%s: mean %.5f against %.5f (%+.2f%%), centre %.5f against %.5f (%+.2f%%), RMS %.2f%%, estimate %.2f%%\n",
              viewpoint ? "seen" : "no viewpoint", mean, mean_exact, 100 * (mean / mean_exact - 1), centre, centre_exact,
              100 * (centre / centre_exact - 1), 100 * rms, 100 * estimate);
  EXPECT_NEAR(mean, mean_exact, 0.01 * mean_exact);
  EXPECT_NEAR(centre, centre_exact, 0.02 * centre_exact);
  EXPECT_GT(estimate, 0.5 * rms);
  EXPECT_LT(estimate, 2.0 * rms);
}

INSTANTIATE_TEST_SUITE_P(Viewpoints, ParallelSquares, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& i) { return i.param ? "Seen" : "NoViewpoint"; });

TEST(DisplayInterpolation, AWindowLitFloorIsExactWhereTheViewpointsLook) {
  Scene s;
  s.source = "a window-lit floor";
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {0, 0, 0}});
  s.materials.push_back({"black", {0, 0, 0}, {0, 0, 0}});
  s.materials.push_back({"window", {0, 0, 0}, {kPi, kPi, kPi}});
  const double size = 4, high = 3;
  s.polygons.push_back(rect(Y, 0, 0, size, 0, size, +1, 0));
  s.polygons.push_back(rect(Y, high, 0, size, 0, size, -1, 1));
  s.polygons.push_back(rect(X, 0, 0, high, 0, size, +1, 1));
  s.polygons.push_back(rect(X, size, 0, high, 0, size, -1, 1));
  s.polygons.push_back(rect(Z, size, 0, size, 0, high, -1, 1));
  s.polygons.push_back(rect(Z, 0, 0, 1.5, 0, high, +1, 1));  // the window wall around a 1 m² window
  s.polygons.push_back(rect(Z, 0, 2.5, size, 0, high, +1, 1));
  s.polygons.push_back(rect(Z, 0, 1.5, 2.5, 0, 1, +1, 1));
  s.polygons.push_back(rect(Z, 0, 1.5, 2.5, 2, high, +1, 1));
  s.polygons.push_back(rect(Z, 0, 1.5, 2.5, 1, 2, +1, 2));  // the window
  s.cameras.push_back({"towards the window", {2, 1.6, 3.5}, normalize(Vec3(0, -1.6, -2.5)), normalize(Vec3(0, 2.5, -1.6)), 1.2, 1.5});
  s.cameras.push_back({"across", {0.5, 1.6, 2}, normalize(Vec3(2.5, -1.6, 0.5)), normalize(Vec3(1.6, 2.5, 0.3)), 1.2, 1.5});
  const test::DefaultBake b("window-floor", std::move(s));
  const Polygon& window = b.scene.polygons.back();
  constexpr int kGrid = 40;
  std::vector<std::pair<Vec3, double>> points;
  double brightest = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const Vec3 p((i + 0.5) * size / kGrid, 0, (j + 0.5) * size / kGrid);
      const double exact = 0.5 * kPi * point_to_polygon(p, {0, 1, 0}, window);
      points.push_back({p, exact});
      brightest = std::max(brightest, exact);
    }
  double worst = 0, squares = 0, reference = 0;
  size_t counted = 0;
  Vec3 at;
  for (const auto& [p, exact] : points) {
    const double baked = baked_at(b, p);
    squares += (baked - exact) * (baked - exact);
    reference += exact * exact;
    if (exact < 0.1 * brightest) continue;
    ++counted;
    const double e = std::fabs(baked / exact - 1);
    if (e > worst) worst = e, at = p;
  }
  const double rms = std::sqrt(squares / reference), estimate = estimated_error(b);
  std::printf("window-lit floor: %zu of %zu points at least a tenth of the brightest, worst %.2f%% at (%.2f, %.2f); "
              "RMS %.2f%%, estimate %.2f%%\n", counted, points.size(), 100 * worst, at.x, at.z, 100 * rms, 100 * estimate);
  EXPECT_GT(counted, points.size() / 2);
  EXPECT_LT(worst, 0.02);
  // The estimate knows the interpolation it leaves (not 0 when the vertices are exact and the faces
  // between them are not).
  EXPECT_GT(estimate, 0.5 * rms);
  EXPECT_LT(estimate, 2.0 * rms);
}

}  // namespace
}  // namespace walkrad
