// ChunkMesh: one streamable piece of a bake as plain arrays, the contract between the pipeline's
// mesher (writes it) and the runtime (reads it). On disk it is a .glb with POSITION, NORMAL,
// COLOR_0 (linear display colour after exposure, clamped to [0, 1]) and _RADIOSITY (physical B, W/m²), an unlit
// material (KHR_materials_unlit) — see docs/architecture.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "walkrad/formats/vec3.h"

namespace walkrad {

struct ChunkMesh {
  std::vector<float> positions;  // xyz per vertex, metres
  std::vector<float> normals;    // xyz per vertex, unit
  std::vector<float> colors;     // rgb per vertex: linear display colour (radiance × exposure)
  std::vector<float> radiosity;  // rgb per vertex: radiosity B, W/m²
  std::vector<uint32_t> indices; // triangles, counter-clockwise seen from the front

  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return indices.size() / 3; }
  Bounds bounds() const;
};

// Reads a chunk written by write_chunk (or any glTF with the same attributes; Draco-compressed
// primitives are decoded). Throws InputError naming the file and the fault.
ChunkMesh read_chunk(const std::string& path);

}  // namespace walkrad
