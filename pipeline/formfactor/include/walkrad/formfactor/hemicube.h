// The hemicube (Cohen & Greenberg 1985), on the CPU: form factors from a point to every polygon of a
// list, with visibility from a z-buffer (algorithms.md §3, "With occlusion").
//
// Around the receiver point stands the upper half of a cube with half-width 1: the full top face
// (z = 1, x, y in [-1, 1], R×R pixels) and four half side faces (R × R/2 pixels each). A pixel of
// area ΔA at (x, y) on the top carries the delta form factor ΔA / (π (x² + y² + 1)²); on a side
// face, at height z and lateral offset y, z ΔA / (π (y² + z² + 1)²). Each polygon is clipped to the
// frustum of each face (the near plane included, so a polygon reaching behind the point never
// projects through infinity), projected, and scan-converted at pixel centres; the nearest polygon
// of each pixel gets the pixel's delta form factor. The error is aliasing, O(1/R) at polygon edges.
#pragma once

#include <vector>

#include "walkrad/formats/scene.h"

namespace walkrad {

// F_dA→P for each polygon, from the point p with unit normal n. A polygon seen from its back
// occludes but gets 0 (only front sides exchange light); a polygon whose plane contains p is
// edge-on and ignored. resolution: the top face's pixels per side, >= 2, rounded up to even.
std::vector<double> hemicube_form_factors(const Vec3& p, const Vec3& n, const std::vector<Polygon>& polygons,
                                          int resolution);

}  // namespace walkrad
