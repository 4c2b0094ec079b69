// Exact unoccluded polygon-to-polygon form factor, the reference that the cheaper estimators
// (element_to_element, Monte Carlo, hemicube) are validated against (algorithms.md §3).
//
// Method: the double contour integral of Stokes' theorem (Sparrow 1963; Goral, Torrance, Greenberg
// & Battaile 1984, eq. 8)
//   A_i F_ij = (1/2π) ∮_{∂i} ∮_{∂j} ln r  dx_i · dx_j,
// with the inner edge integral in closed form and the outer one by adaptive Gauss-Kronrod quadrature
// split where two edges meet (Mazumder & Ravishankar 2012). Schröder & Hanrahan (1993) give the outer
// integral in closed form too (dilogarithms); the adaptive 1-D quadrature reaches the same digits
// and stays simple where edges touch or overlap.
#pragma once

#include "walkrad/formats/scene.h"

namespace walkrad {

// F_ij from receiver i to source j, unoccluded, one-sided: each polygon's front is the side its
// winding makes counter-clockwise (scene.h), and only the part of each polygon in front of the
// other's plane exchanges light (a receiver behind the source's plane gets 0). Orientation of the
// contours is handled internally: the result never turns negative whatever the vertex order, and
// does not depend on which vertex comes first. Coplanar or degenerate pairs give 0, never NaN.
// Touching pairs (a shared edge, a shared vertex, polygons that cut through each other) are exact.
// tolerance: absolute error target on F (> 0); the usual error is far below it.
double polygon_to_polygon_exact(const Polygon& receiver, const Polygon& source, double tolerance = 1e-9);

}  // namespace walkrad
