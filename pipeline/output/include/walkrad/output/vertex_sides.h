// The sides of the walls standing on a surface, at each output vertex. Two rooms' floors that meet
// under a wall of no thickness (or a floor and the corridor's past a door wall) are one smoothing
// group, and the vertex on the wall's foot would average the two rooms' light and be read from a point
// on the wall itself, whose rays start on it: the floor 10 cm from the wall of a lit room read 40%
// dark. Around such a vertex the walls' edges that lie in the surface's plane cut the plane into
// sectors; the faces of one group in different sectors take different vertices (radiosity is
// discontinuous across a wall physically), each read from its own side. Where nothing stands, or a
// single wall ends at the vertex (a door jamb's foot: light passes round it), every face shares one.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/output/surface_mesher.h"

namespace walkrad {

// For every face's boundary entry (boundary[boundary_begin[i] .. boundary_begin[i + 1]) for face i:
// point ids into points), the sector of the face around that point, 0 where the point has one; group:
// each scene polygon's smoothing group. tol: lengths below it are 0 (the mesher's weld tolerance).
std::vector<uint8_t> vertex_sides(const MeshFaces& faces, const std::vector<Vec3>& points, const uint32_t* boundary,
                                  const uint32_t* boundary_begin, const std::vector<uint32_t>& group, double tol);

}  // namespace walkrad
