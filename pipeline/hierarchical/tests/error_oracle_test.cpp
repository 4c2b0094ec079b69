// The refinement's oracle on its own (error_oracle.h): the white and the tolerances it derives from the
// radiosity shown, the variation a link's shares leave over a receiver's children, and the bound a
// wholly hidden link is held to. Hand-made hierarchies with hand-set radiosity and links: the
// arithmetic of error_estimate.cpp, checked against the numbers worked out here.
#include <cmath>

#include <gtest/gtest.h>

#include "error_oracle.h"
#include "two_squares.h"

namespace walkrad::hierarchical_detail {
namespace {

// The two squares (two_squares.h), neither emitting, their radiosity set by hand.
struct TwoSquares : test::TwoSquares {
  void shine(uint32_t node, double b) { (*h)[node].B = (*h)[node].Bt = Vec3(b, b, b); }
};

TEST(ErrorOracle, TolerancesFollowWhatEachSurfaceShows) {
  TwoSquares t;
  t.settings.error = 0.05;
  t.shine(t.lower, 0.9);
  t.shine(t.upper, 0.009);  // far below a tenth of the white
  ErrorOracle oracle(*t.h, t.settings, 1e-4);
  EXPECT_FALSE(oracle.worth_splitting(t.lower, t.upper, true)) << "nothing is worth splitting before the white is known";
  oracle.update_scales();
  // Without importance every node weighs 1, and the white is the 95th percentile of the leaves'
  // luminance by area (the brighter square) mapped to 0.9.
  EXPECT_DOUBLE_EQ(oracle.display_weight(t.lower), 1.0);
  EXPECT_NEAR(oracle.state().white, 1.0, 1e-12);
  EXPECT_NEAR(oracle.tolerance(t.lower), 0.05 * 0.9, 1e-12);
  EXPECT_NEAR(oracle.tolerance(t.upper), 0.05 * 0.1, 1e-12) << "a dark surface is held to a tenth of the white";
}

TEST(ErrorOracle, TheVariationIsWhatTheSharesLeaveAtTheWorstChild) {
  // One link from the upper square (B = 2) to the lower, F = 0.1, falling unevenly on the receiver's
  // quadrants (shares 1.5, 0.5, 1, 1): H = 0.2, its children's 0.3, 0.1, 0.2, 0.2. The refinement's
  // test is ρ |H_c − H| at the worst child, 0.5 × 0.1; the estimate's, the RMS that leaves inside the
  // children, ρ √(Σ (H_c − H)² / 4 / 3).
  TwoSquares t;
  t.shine(t.lower, 0.1);
  t.shine(t.upper, 2.0);
  Link l;
  l.F = 0.1f;
  l.source = t.upper;
  l.share = {1.5f, 0.5f, 1.0f, 1.0f};
  (*t.h)[t.lower].links.push_back(l);
  ErrorOracle oracle(*t.h, t.settings, 1e-4);
  oracle.update_scales();
  oracle.measure_variation();
  EXPECT_NEAR(oracle.state().variation[t.lower], 0.5 * 0.1, 1e-6);
  EXPECT_NEAR(oracle.state().left[t.lower], 0.5 * std::sqrt((0.01 + 0.01) / 4.0 / 3.0), 1e-6);
  EXPECT_EQ(oracle.state().variation[t.upper], 0.0f) << "a node without links varies by nothing";
  // Shares that sum to a uniform transfer leave nothing to refine, however much the link carries.
  (*t.h)[t.lower].links[0].share = {1, 1, 1, 1};
  oracle.measure_variation();
  EXPECT_EQ(oracle.state().variation[t.lower], 0.0f);
}

TEST(ErrorOracle, AHiddenLinkIsHeldToWhatItsRaysCouldHaveMissed) {
  // A link whose every ray was blocked carries, at most, kHiddenBound σ of its source: split while that
  // much would matter, kept once it would not. The threshold scales with the quantum area.
  TwoSquares t;
  t.shine(t.lower, 1.0);
  t.shine(t.upper, 1.0);
  Link hidden;
  hidden.source = t.upper;
  hidden.F = 0;
  const double quantum = 1e-3;
  ErrorOracle oracle(*t.h, t.settings, quantum);
  oracle.update_scales();
  // carried = ρ × B × kHiddenBound σ × A × weight against e × white × quantum: the σ at which the two meet.
  const double white = oracle.state().white;
  const double sigma_at = t.settings.error * white * quantum / (0.5 * 1.0 * ErrorOracle::kHiddenBound * 1.0);
  hidden.sigma = float(2.0 * sigma_at);
  EXPECT_TRUE(oracle.worth_splitting(t.lower, t.upper, true, &hidden));
  hidden.sigma = float(0.5 * sigma_at);
  EXPECT_FALSE(oracle.worth_splitting(t.lower, t.upper, true, &hidden));
  // A uniform source in full view is never split for what it carries (the contour formula is exact).
  EXPECT_FALSE(oracle.worth_splitting(t.lower, t.upper, false));
}

}  // namespace
}  // namespace walkrad::hierarchical_detail
