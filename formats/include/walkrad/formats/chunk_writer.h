// write_chunk: a ChunkMesh as a binary glTF (.glb) that any viewer shows and the Khronos validator
// accepts: POSITION (with min/max), NORMAL, COLOR_0, _RADIOSITY, uint32 indices, one unlit material.
// Formats write side: the runtime never links it.
#pragma once

#include <cstdint>
#include <string>

#include "walkrad/formats/chunk.h"

namespace walkrad {

// Writes the chunk and returns its size in bytes. Throws OutputError when the file cannot be written.
uint64_t write_chunk(const std::string& path, const ChunkMesh& mesh);

}  // namespace walkrad
