// From the hierarchy's solution to a displayable mesh: the leaves of every element quadtree are the
// faces of a crack-free Gouraud mesh (surface_mesher.h: T-vertices anchored, vertex radiosity averaged
// over the leaves around each vertex, within a smoothing group).
#pragma once

#include "walkrad/formats/chunk.h"
#include "walkrad/pipeline/hierarchy.h"
#include "walkrad/pipeline/vertex_mesher.h"

namespace walkrad {

// exposure: display colour = B/π × exposure, clamped to [0, 1].
SurfaceMesh mesh_hierarchy(const Hierarchy& h, double exposure);

// The leaf element containing a point of an input polygon (for exposure and tests).
// (max_depth: stop at that quadtree depth even if the node there has children.)
uint32_t leaf_at(const Hierarchy& h, uint32_t polygon_root, const Vec3& p, int max_depth = 255);

}  // namespace walkrad
