// From the hierarchy's solution to a displayable mesh: the leaves of every element quadtree become
// triangles; a vertex's radiosity is the area-weighted average of the leaves of its input polygon
// that share it (Gouraud, algorithms.md §8). Leaves of different depths meet at T-vertices: the
// crack-free anchoring of a restricted quadtree is issue 5's work.
#pragma once

#include "walkrad/formats/chunk.h"
#include "walkrad/pipeline/hierarchy.h"
#include "walkrad/pipeline/vertex_mesher.h"

namespace walkrad {

// exposure: display colour = B/π × exposure, clamped to [0, 1].
SurfaceMesh mesh_hierarchy(const Hierarchy& h, double exposure);

// The leaf element containing a point of an input polygon (for exposure and tests).
uint32_t leaf_at(const Hierarchy& h, uint32_t polygon_root, const Vec3& p);

}  // namespace walkrad
