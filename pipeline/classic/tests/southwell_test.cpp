// Progressive refinement (southwell.h) against the furnace's exact answer, against Gauss-Seidel on a
// lit room, and its ambient term: after one shot per element, what is shown is already near the answer.
#include <cmath>

#include <gtest/gtest.h>

#include "walkrad/classic/form_factor_matrix.h"
#include "walkrad/classic/gauss_seidel.h"
#include "walkrad/classic/southwell.h"
#include "walkrad/classic/subdivision.h"
#include "walkrad/testing/test_scenes.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {
namespace {

struct System {
  Subdivision sub;
  FormFactorMatrix f;
  std::vector<double> area;
  std::vector<Vec3> rho, emission;
};

System make_system(const Scene& scene, double element_size) {
  System s;
  s.sub = subdivide_uniform(scene, element_size);
  const RayScene rays(scene);
  FormFactorCounts counts;
  s.f = compute_form_factors(s.sub, &rays, nullptr, {}, counts);
  for (const Element& e : s.sub.elements) {
    const Material& m = scene.materials[e.shape.material];
    s.area.push_back(e.area);
    s.rho.push_back(m.reflectance);
    s.emission.push_back(m.emission);
  }
  return s;
}

class SouthwellFurnace : public ::testing::TestWithParam<double> {};

TEST_P(SouthwellFurnace, ConvergesToEOverOneMinusRho) {
  const double rho = GetParam();
  const Vec3 e(1.0, 2.0, 0.5);
  const System s = make_system(test::closed_box(2.0, {rho, rho, rho}, e), 0.5);
  SouthwellStats stats;
  const std::vector<Vec3> b = solve_southwell(s.f, s.area, s.rho, s.emission, {}, stats);
  ASSERT_TRUE(stats.converged);
  std::printf("southwell furnace ρ %g: %llu shots for %zu elements, unshot %.1e\n", rho,
              static_cast<unsigned long long>(stats.shots), b.size(), stats.unshot);
  const Vec3 exact = e / (1.0 - rho);
  for (size_t i = 0; i < b.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(b[i][c], exact[c], 1e-3 * exact[c]) << "element " << i << " channel " << c;
  const EnergyBalance eb = energy_balance(s.f, s.area, s.rho, s.emission, b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(eb.absorbed[c], eb.emitted[c], 1e-3 * eb.emitted[c]);
}

INSTANTIATE_TEST_SUITE_P(Reflectances, SouthwellFurnace, ::testing::Values(0.5, 0.9, 0.99));

// One shot per element leaves most of the furnace's light unshot (ρ = 0.9: B = 10 E, and one round of
// shots gives about 2 E), but the ambient term shows it: the mean displayed radiosity is within 5%.
TEST(Southwell, AmbientTermShowsWhatIsNotShotYet) {
  const System s = make_system(test::closed_box(2.0, {0.9, 0.9, 0.9}, {1, 1, 1}), 0.5);
  SouthwellSettings early;
  early.max_shots = s.area.size();
  double shown[2];
  for (const bool ambient : {false, true}) {
    early.ambient = ambient;
    SouthwellStats stats;
    const std::vector<Vec3> b = solve_southwell(s.f, s.area, s.rho, s.emission, early, stats);
    EXPECT_FALSE(stats.converged);
    double sum = 0, area = 0;
    for (size_t i = 0; i < b.size(); ++i) {
      sum += b[i].x * s.area[i];
      area += s.area[i];
    }
    shown[ambient] = sum / area;
  }
  std::printf("furnace ρ 0.9 after one shot per element: mean B %.3f without the ambient term, %.3f with (exact 10)\n",
              shown[0], shown[1]);
  EXPECT_LT(shown[0], 5.0);
  EXPECT_NEAR(shown[1], 10.0, 0.5);
}

// A room lit by one ceiling face with a block inside: shooting and gathering reach the same solution.
TEST(Southwell, AgreesWithGaussSeidel) {
  Scene room = test::closed_box(2.0, {0.6, 0.5, 0.4}, {0, 0, 0});
  room.materials.push_back({"lamp", {0.3, 0.3, 0.3}, {5, 5, 5}});
  room.polygons[1].material = 1;
  test::add_cube(room, {1, 0.5, 1}, 0.6);
  const System s = make_system(room, 0.4);
  SouthwellSettings sw;
  sw.tolerance = 1e-10;
  SouthwellStats sws;
  const std::vector<Vec3> a = solve_southwell(s.f, s.area, s.rho, s.emission, sw, sws);
  SolveSettings gs;
  gs.tolerance = 1e-10;
  SolveStats gss;
  const std::vector<Vec3> b = solve_gauss_seidel(s.f, s.area, s.rho, s.emission, gs, gss);
  ASSERT_TRUE(sws.converged && gss.converged);
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(a[i][c] - b[i][c]) / std::max(b[i][c], 1e-3));
  std::printf("southwell vs gauss-seidel: %llu shots, %d sweeps, largest relative difference %.1e\n",
              static_cast<unsigned long long>(sws.shots), gss.iterations, worst);
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace walkrad
