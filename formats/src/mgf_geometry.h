// Geometry for the MGF reader (mgf_reader.h): MGF faces (any number of vertices, concave, with
// seams or holes) split into the planar convex triangles and quads of scene.h, and MGF's curved
// primitives tessellated into faces.
#pragma once

#include <string>
#include <vector>

#include "walkrad/formats/vec3.h"

namespace walkrad::mgf {

using Loop = std::vector<Vec3>;  // a polygon's vertices in order, counter-clockwise from its front

struct SplitResult {
  std::vector<Loop> pieces;  // convex planar triangles and quads, same orientation as the input
  bool degenerate = false;   // no area at all: nothing in pieces
  bool nonplanar = false;    // the input was not planar: it was split into triangles
  bool untriangulated = false;  // a self-intersecting outline: only part of it is in pieces
};

// Splits a face. A planar convex face becomes one quad or triangle or a fan of quads (collinear
// corners dropped); any other face is ear-clipped into triangles in its best-fit plane (Eberly,
// "Triangulation by Ear Clipping", Geometric Tools 2002). MGF's seams (a hole joined to the outline
// by an edge traversed both ways, the MGF spec's entity "f") are triangulated like any outline.
SplitResult split_face(const Loop& face);

// Joins holes to an outline with bridge edges (Eberly 2002, §3: the hole's rightmost vertex to a
// visible outline vertex), giving one loop with seams for split_face. The holes' own orientation
// does not matter. Returns false with a reason when a hole is not inside the outline.
bool join_holes(const Loop& outline, const std::vector<Loop>& holes, Loop& joined, std::string& why);

// Curved primitives, in the frame their vertices are given in (the caller transforms the loops as
// it transforms faces). divisions: segments per quarter circle. Each returns faces oriented
// outwards, or inwards where the MGF spec says so (negative radii, negative prism length).
// MGF's segments per quarter circle for a chord that leaves the true curve by at most
// tolerance × radius: ceil((π/2) / (2·acos(1 - tolerance))). 0.02 gives RenderPark's 4.
int quarter_divisions(double tolerance);
// Sphere about centre c, poles on the z axis; radius < 0: inward.
void tessellate_sphere(const Vec3& c, double radius, int divisions, std::vector<Loop>& out);
// Truncated cone (cylinder when r1 == r2) between axis points p1 and p2, open-ended. Radii of one
// sign (or zero), not both zero; negative: inward. A zero radius gives triangles.
void tessellate_cone(const Vec3& p1, double r1, const Vec3& p2, double r2, int divisions, std::vector<Loop>& out);
// Disc (rmin = 0) or annulus in the plane through c normal to n, facing n. 0 <= rmin < rmax.
void tessellate_ring(const Vec3& c, const Vec3& n, double rmin, double rmax, int divisions, std::vector<Loop>& out);
// Torus around the axis through c along n, from distance |rmin| to |rmax| from the axis; both
// negative: inward.
void tessellate_torus(const Vec3& c, const Vec3& n, double rmin, double rmax, int divisions, std::vector<Loop>& out);
// Closed prism: the base face (counter-clockwise about its normal N), a copy moved by -length·N
// and the sides. Negative length: inward.
void tessellate_prism(const Loop& base, double length, std::vector<Loop>& out);

}  // namespace walkrad::mgf
