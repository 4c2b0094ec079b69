// Reference form factors in closed form from Howell's catalogue of configuration factors
// (J. R. Howell, "A Catalog of Radiation Heat Transfer Configuration Factors", 3rd ed., cases C-11
// and C-14; also Siegel & Howell, "Thermal Radiation Heat Transfer", appendix C), and the
// polygons that realise them, for the form factor estimators' tests.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "walkrad/testing/test_scenes.h"

namespace walkrad::test {


// C-11: parallel, directly opposed rectangles a × b at distance c, F from one to the other.
inline double howell_c11(double a, double b, double c) {
  const double x = a / c, y = b / c, x2 = x * x, y2 = y * y;
  const double sx = std::sqrt(1 + x2), sy = std::sqrt(1 + y2);
  return 2.0 / (kPi * x * y) *
         (0.5 * std::log((1 + x2) * (1 + y2) / (1 + x2 + y2)) + x * sy * std::atan(x / sy) +
          y * sx * std::atan(y / sx) - x * std::atan(x) - y * std::atan(y));
}

// C-14: rectangles at 90° sharing an edge of length l; F from the one of width w (across the
// common edge) to the one of height h.
inline double howell_c14(double l, double w, double h) {
  const double W = w / l, H = h / l, W2 = W * W, H2 = H * H, S2 = W2 + H2, S = std::sqrt(S2);
  const double log_term = std::log((1 + W2) * (1 + H2) / (1 + S2)) +
                          W2 * std::log(W2 * (1 + S2) / ((1 + W2) * S2)) +
                          H2 * std::log(H2 * (1 + S2) / ((1 + H2) * S2));
  return (W * std::atan(1 / W) + H * std::atan(1 / H) - S * std::atan(1 / S) + 0.25 * log_term) / (kPi * W);
}

// A point on the axis of a regular N-gon of circumradius r, at height h, facing it (Lambert's
// contour formula summed over N equal edges): F = (N/π) (a/d) atan(s/d), with apothem a, half-edge
// s, d = sqrt(a² + h²). Tends to the disc's r² / (r² + h²) as N grows, with error O(1/N²).
inline double regular_ngon_on_axis(int n, double r, double h) {
  const double a = r * std::cos(kPi / n), s = r * std::sin(kPi / n), d = std::sqrt(a * a + h * h);
  return n / kPi * (a / d) * std::atan(s / d);
}

inline double disc_on_axis(double r, double h) { return r * r / (r * r + h * h); }

// C-11's rectangles: `lower` in y = 0 facing +y, `upper` in y = c facing −y, both over [0,a]×[0,b] in x, z.
struct RectanglePair {
  Polygon first, second;
};

inline RectanglePair parallel_rectangles(double a, double b, double c) {
  return {quad({0, 0, 0}, {0, 0, b}, {a, 0, b}, {a, 0, 0}), quad({0, c, 0}, {a, c, 0}, {a, c, b}, {0, c, b})};
}

// C-14's rectangles: a floor (y = 0, facing +y, x in [0, w]) and a wall (x = 0, facing +x, y in
// [0, h]) sharing the edge x = y = 0, z in [0, l].
inline RectanglePair perpendicular_rectangles(double l, double w, double h) {
  return {quad({0, 0, 0}, {0, 0, l}, {w, 0, l}, {w, 0, 0}), quad({0, 0, 0}, {0, h, 0}, {0, h, l}, {0, 0, l})};
}

// A number with 3 significant digits, for test case names in failure messages.
inline std::string str(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

}  // namespace walkrad::test
