// meshoptimizer on every chunk before it is written (Kapoulkine's meshoptimizer): triangles reordered
// for the post-transform vertex cache (Forsyth's method), then for overdraw (Sander, Nehab & Barczak
// 2007, "Fast triangle reordering for vertex locality and reduced overdraw") within 5% of the cache
// optimum, then vertices renumbered in order of first use (vertex fetch). The mesh is the same set of
// triangles and vertices: only their order changes, deterministically.
#pragma once

#include "walkrad/formats/chunk.h"

namespace walkrad {

void optimize_chunk(ChunkMesh& mesh);

}  // namespace walkrad
