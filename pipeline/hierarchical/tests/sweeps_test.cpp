// The transport on its own (sweeps.h): two facing squares joined by hand-made links, swept to their
// fixed point, against the 2 × 2 radiosity system solved in closed form; Gauss-Seidel and Jacobi
// reach the same one, and a sweep's energy terms are what the leaves' equations say.
#include <cmath>
#include <utility>

#include <gtest/gtest.h>

#include "sweeps.h"
#include "two_squares.h"

namespace walkrad::hierarchical_detail {
namespace {

// The two squares, the lower emitting E = 1, linked both ways with Howell's C-11 form factor (equal
// areas: F12 = F21).
struct LinkedSquares : test::TwoSquares {
  double F = test::howell_c11(1.0, 1.0, 1.0);

  LinkedSquares() : TwoSquares(1.0) {
    for (const auto& [to, from] : {std::pair{lower, upper}, std::pair{upper, lower}}) {
      Link l;
      l.F = float(F);
      l.source = from;
      (*h)[to].links.push_back(l);
    }
  }
};

TEST(Sweeps, ReachTheClosedFormFixedPoint) {
  // B1 = E + ρ F B2, B2 = ρ F B1: B1 = E / (1 − (ρF)²), B2 = ρ F B1 (F as the link stores it, a float).
  for (const bool gauss_seidel : {true, false}) {
    LinkedSquares t;
    t.settings.gauss_seidel = gauss_seidel;
    const double rf = 0.5 * double(float(t.F));
    const double b1 = 1.0 / (1.0 - rf * rf), b2 = rf * b1;
    ErrorOracle oracle(*t.h, t.settings, 1e-4);
    Sweeps sweeps(*t.h, t.settings, oracle, Division{});
    sweeps.measure_change_floor();
    if (gauss_seidel) sweeps.plan_gather_blocks();
    double change = 1;
    IterationStats is;
    for (int k = 0; k < 40 && change > 1e-15; ++k) change = sweeps.sweep(is);
    EXPECT_NEAR((*t.h)[t.lower].B.y, b1, 1e-12) << (gauss_seidel ? "Gauss-Seidel" : "Jacobi");
    EXPECT_NEAR((*t.h)[t.upper].B.y, b2, 1e-12) << (gauss_seidel ? "Gauss-Seidel" : "Jacobi");
    // At the fixed point the leaves absorb (1 − ρ) of what reaches them; E is what is emitted.
    EXPECT_NEAR(is.emitted.y, 1.0, 1e-12);
    EXPECT_NEAR(is.absorbed.y, 0.5 * (t.F * b2 + t.F * b1), 1e-6);
    EXPECT_LT(is.residual.y, 1e-12);
  }
}

TEST(Sweeps, GaussSeidelConvergesInFewerSweepsThanJacobi) {
  // Each Gauss-Seidel sweep reads what the polygons before it got this sweep: its change falls by
  // (ρF)² a sweep, Jacobi's by ρF.
  int sweeps_needed[2] = {0, 0};
  for (const bool gauss_seidel : {true, false}) {
    LinkedSquares t;
    t.settings.gauss_seidel = gauss_seidel;
    ErrorOracle oracle(*t.h, t.settings, 1e-4);
    Sweeps sweeps(*t.h, t.settings, oracle, Division{});
    sweeps.measure_change_floor();
    if (gauss_seidel) sweeps.plan_gather_blocks();
    IterationStats is;
    int& n = sweeps_needed[gauss_seidel ? 0 : 1];
    for (double change = 1; change > 1e-9 && n < 100; ++n) change = sweeps.sweep(is);
  }
  EXPECT_LT(sweeps_needed[0], sweeps_needed[1]);
}

}  // namespace
}  // namespace walkrad::hierarchical_detail
