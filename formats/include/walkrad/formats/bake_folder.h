// A bake folder read as a whole: its manifest and all of its chunks as one mesh (for `walkrad diff`,
// benches and tests; the runtime streams chunk by chunk instead).
#pragma once

#include <string>

#include "walkrad/formats/chunk.h"
#include "walkrad/formats/manifest.h"

namespace walkrad {

// Appends b's vertices and triangles to a (b's indices shifted past a's vertices).
void append_mesh(ChunkMesh& a, const ChunkMesh& b);

// Every chunk the folder's manifest.json lists, in manifest order, as one mesh. Throws InputError.
ChunkMesh read_bake_mesh(const std::string& folder);

}  // namespace walkrad
