// How far apart two computed points may be and still be the same point: coordinates of magnitude m
// carry rounding of about m × 2⁻⁵³ from every operation on them (a contact cut, a bilinear split), so
// geometric tests ("on this plane?", "touching this box?") need a slack that grows with m as well as
// one relative to the objects' own size. 256 ulps: far above what a few operations accumulate, and
// still 1e-8 m at 1e5 m from the origin (see docs/numerics.md).
#pragma once

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "walkrad/formats/vec3.h"

namespace walkrad {

// Discrete choices taken on ratios of computed lengths (a quadrature order, which end of a link to
// split, whether two nodes are near) meet exact ties in regular geometry (a 0.5 m element 1 m from
// another): decided by rounding, the same scene scaled or moved would decide otherwise and refine
// differently. A tie within 1e-9 counts as "not greater", whatever the units.
inline bool clearly_greater(double a, double b) { return a > b + 1e-7 * std::fabs(b); }

inline double rounding_at(const Vec3& p) {
  return 256 * DBL_EPSILON * std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
}

}  // namespace walkrad
