// Convex polygons of any corner count while they are being cut (contact_split.h, the output's
// discontinuity cuts: face_cuts.h), and back to the scene's polygons of at most 4 corners.
#pragma once

#include <vector>

#include "walkrad/formats/scene.h"

namespace walkrad {

using Loop = std::vector<Vec3>;  // a convex polygon's corners, counter-clockwise

double loop_area(const Loop& l);

// Splits a convex loop by the plane dot(x, n) = d (n unit) into the parts on either side (either may be
// empty; a corner on the plane goes to both). A corner within tol of the plane counts as on it, so that
// no new corner falls within tol of an old one.
void split_loop(const Loop& l, const Vec3& n, double d, Loop& below, Loop& above, double tol = 0);

// The part [t0, t1] of segment [a, b] (in the plane of the convex polygon corners[0..n), unit normal
// `normal`, counter-clockwise around it) that lies inside the polygon; false when none does.
bool clip_segment(const Vec3* corners, size_t n, const Vec3& normal, const Vec3& a, const Vec3& b, double& t0, double& t1);

// Appends l as a fan of quads (and a last triangle) from l[0], each a copy of `like` with new corners:
// convex pieces of a convex loop. Pieces of zero area are left out.
void emit_loop(const Loop& l, const Polygon& like, std::vector<Polygon>& out);

}  // namespace walkrad
