// The sweep's error measures (error_measures.h) on hand-computed cases.
#include <cmath>

#include <gtest/gtest.h>

#include "walkrad/accuracy/error_measures.h"

namespace walkrad {
namespace {

TEST(Accuracy, RelativeErrorsOnAHandComputedCase) {
  // Reference 1, 2, NaN (left out), 3; bake 1.5, 2, 7, 2.
  const std::vector<double> r = {1, 2, NAN, 3}, a = {1.5, 2, 7, 2}, w = {2, 1, 5, 1};
  const ErrorMeasures e = relative_errors(a, r, w);
  EXPECT_EQ(e.points, 3u);
  EXPECT_NEAR(e.rms, std::sqrt((0.25 + 0 + 1) / (1 + 4 + 9)), 1e-12);
  EXPECT_NEAR(e.rms_weighted, std::sqrt((2 * 0.25 + 1) / (2 * 1 + 4 + 9)), 1e-12);
  EXPECT_NEAR(e.max, 1.0 / 2.0, 1e-12);  // |3 − 2| / mean(1, 2, 3)
  // Weights relative to their mean (4/3): 1.5, 0.75, 0.75; largest weighted |a − r| = 0.75; Σwr/Σw = 7/4.
  EXPECT_NEAR(e.max_weighted, 0.75 / (7.0 / 4.0), 1e-12);
  EXPECT_NEAR(e.bias, (2 * 0.5 + 0 - 1) / (2 * 1 + 2 + 3.0), 1e-12);
}

TEST(Accuracy, ReferenceErrorBarIsTheRelativeRmsOfTheHalfWidths) {
  const ErrorMeasures e = reference_error_bar({2, 4}, {0.1, 0.2});
  EXPECT_NEAR(e.rms, 1.96 * std::sqrt((0.01 + 0.04) / (4 + 16)), 1e-12);
  EXPECT_EQ(e.points, 2u);
}

}  // namespace
}  // namespace walkrad
