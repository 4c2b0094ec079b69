// The furnace: a closed box whose faces all emit E and reflect ρ has B = E / (1 − ρ) everywhere
// (algorithms.md §4: the Neumann series Σ ρ^k E). Exercises subdivision, Embree visibility (every
// ray must arrive), the form factor matrix and the solver together.
#include <cmath>

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/classic/form_factor_matrix.h"
#include "walkrad/classic/gauss_seidel.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/classic/subdivision.h"

namespace walkrad {
namespace {

class Furnace : public ::testing::TestWithParam<double> {};

TEST_P(Furnace, ConvergesToEOverOneMinusRho) {
  const double rho = GetParam();
  const Vec3 e(1.0, 2.0, 0.5);
  const Scene box = test::closed_box(2.0, {rho, rho, rho}, e);
  const Subdivision sub = subdivide_uniform(box, 0.5);
  const RayScene rays(box);
  FormFactorCounts counts;
  FormFactorSettings settings;
  settings.rays_per_point = 2;
  const FormFactorMatrix f = compute_form_factors(sub, &rays, /*tree=*/nullptr, settings, counts);
  EXPECT_GT(counts.rays, 0u);

  std::vector<Vec3> rhos(sub.elements.size(), {rho, rho, rho}), es(sub.elements.size(), e);
  SolveStats stats;
  const std::vector<Vec3> b = solve_gauss_seidel(f, rhos, es, {}, stats);
  ASSERT_TRUE(stats.converged);
  const Vec3 exact = e / (1.0 - rho);
  for (size_t i = 0; i < b.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(b[i][c], exact[c], 1e-3 * exact[c]) << "element " << i << " channel " << c;

  // Power balance: all emitted power is absorbed.
  std::vector<double> area;
  for (const Element& el : sub.elements) area.push_back(el.area);
  const EnergyBalance eb = energy_balance(f, area, rhos, es, b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(eb.absorbed[c], eb.emitted[c], 1e-4 * eb.emitted[c]);
}

INSTANTIATE_TEST_SUITE_P(Reflectances, Furnace, ::testing::Values(0.5, 0.9));

}  // namespace
}  // namespace walkrad
