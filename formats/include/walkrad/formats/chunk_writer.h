// write_chunk: a ChunkMesh as a binary glTF (.glb) that any viewer shows and the Khronos validator
// accepts: POSITION (with min/max), NORMAL, COLOR_0, _RADIOSITY, uint32 indices, one unlit material;
// plain, or compressed with Draco (KHR_draco_mesh_compression).
//
// Draco quantises each attribute on a grid. The grids come from error budgets (draco_encoding) and
// are shared by every chunk of a bake, so a vertex on the border of two chunks lands on the same
// point in both (no crack between chunks), and the error bound holds everywhere.
// Formats write side: the runtime never links it.
#pragma once

#include <cstdint>
#include <string>

#include "walkrad/formats/chunk.h"

namespace walkrad {

// A quantisation grid: values in [origin, origin + range] on 2^bits − 1 steps; max error range / (2^bits − 1) / 2.
struct QuantGrid {
  float origin[3] = {0, 0, 0};
  float range = 1;
  int bits = 16;
  double max_error() const { return double(range) / double((uint64_t(1) << bits) - 1) / 2; }
};

struct ChunkEncoding {
  bool draco = false;
  QuantGrid position, color, radiosity;
  int normal_bits = 10;  // octahedral
  int speed = 5;         // Draco's encoding/decoding speed, 0 (smallest) … 10 (fastest)
};

// The grids for a bake: positions over its bounds with error ≤ position_tolerance (metres); display
// colours in [0, 1] with error ≤ 0.5/255 after sRGB encoding (the encoding's slope is at most 12.92);
// radiosity in [0, radiosity_max] with error ≤ radiosity_tolerance (W/m²). At most 30 bits each.
ChunkEncoding draco_encoding(const Bounds& bounds, double position_tolerance, double radiosity_max,
                             double radiosity_tolerance);

// Writes the chunk and returns its size in bytes. Throws OutputError when the file cannot be written.
uint64_t write_chunk(const std::string& path, const ChunkMesh& mesh, const ChunkEncoding& encoding = {});

}  // namespace walkrad
