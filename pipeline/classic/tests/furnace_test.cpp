// The furnace: a closed box whose faces all emit E and reflect ρ has B = E / (1 − ρ) everywhere
// (algorithms.md §4: the Neumann series Σ ρ^k E). Exercises subdivision, Embree visibility (every
// ray must arrive), the form factor matrix and the solver together.
#include <cmath>

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/classic/form_factor_matrix.h"
#include "walkrad/classic/gauss_seidel.h"
#include "walkrad/formfactor/form_factor.h"
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

// The hemicube's matrix (FormFactorSettings::hemicube): from each element's centroid every other element
// by its z-buffer. In a closed box each row sums to 1 up to the pixels' aliasing, each entry is the
// contour formula from the centroid (nothing occludes in a box) up to it, and the furnace comes out
// within it of E / (1 − ρ).
TEST(HemicubeMatrix, RowsSumToOneAndTheFurnaceHolds) {
  const double rho = 0.9;
  const Scene box = test::closed_box(2.0, {rho, rho, rho}, {1, 1, 1});
  const Subdivision sub = subdivide_uniform(box, 0.5);
  const RayScene rays(box);
  FormFactorCounts counts;
  FormFactorSettings hemicube;
  hemicube.hemicube = 128;
  const FormFactorMatrix f = compute_form_factors(sub, &rays, nullptr, hemicube, counts);
  EXPECT_EQ(counts.rays, 0u);
  double worst_row = 0, worst_entry = 0;
  for (size_t i = 0; i < f.rows(); ++i) {
    worst_row = std::max(worst_row, std::fabs(f.row_sum(i) - 1));
    const Element& e = sub.elements[i];
    for (uint64_t k = f.row_start[i]; k < f.row_start[i + 1]; ++k) {
      const double exact = point_to_polygon(e.centroid, e.normal, sub.elements[f.column[k]].shape);
      if (exact > 2e-2) worst_entry = std::max(worst_entry, std::fabs(f.value[k] - exact) / exact);
    }
  }
  std::printf("hemicube 128: worst row sum off 1 by %.2e, worst entry (F > 0.02: over 250 pixels) off the contour formula's by %.2f%%\n",
              worst_row, 100 * worst_entry);
  EXPECT_LT(worst_row, 5e-3);
  EXPECT_LT(worst_entry, 0.05);
  std::vector<Vec3> rhos(sub.elements.size(), {rho, rho, rho}), es(sub.elements.size(), {1, 1, 1});
  SolveStats stats;
  const std::vector<Vec3> b = solve_gauss_seidel(f, rhos, es, {}, stats);
  ASSERT_TRUE(stats.converged);
  for (size_t i = 0; i < b.size(); ++i) ASSERT_NEAR(b[i].x, 10.0, 10.0 * 10 * worst_row + 1e-9) << "element " << i;
}

}  // namespace
}  // namespace walkrad
