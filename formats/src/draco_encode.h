// A ChunkMesh compressed with Draco (formats' write side), and what its decoder will give back, which a
// glTF file must declare (counts, POSITION bounds).
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/chunk.h"
#include "walkrad/formats/chunk_writer.h"

namespace walkrad {

struct DracoChunk {
  std::vector<uint8_t> bytes;
  int position_id = -1, normal_id = -1, color_id = -1, radiosity_id = -1;  // Draco attribute unique ids
  size_t vertices = 0, triangles = 0;   // as decoded
  Bounds bounds;                        // of the decoded (quantised) positions
};

// Throws OutputError when Draco refuses the mesh.
DracoChunk draco_encode(const ChunkMesh& mesh, const ChunkEncoding& encoding, const std::string& path);

}  // namespace walkrad
