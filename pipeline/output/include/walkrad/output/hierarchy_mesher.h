// From the hierarchy's solution to a displayable mesh: the leaves of every element quadtree are the
// faces of a crack-free Gouraud mesh (surface_mesher.h: T-vertices anchored, vertex radiosity averaged
// over the leaves around each vertex, within a smoothing group).
#pragma once

#include "walkrad/formats/chunk.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/output/surface_mesher.h"

namespace walkrad {

// exposure: display colour = B/π × exposure, clamped to [0, 1].
SurfaceMesh mesh_hierarchy(const Hierarchy& h, double exposure);

}  // namespace walkrad
