// GpuMesh: a ChunkMesh copied to the GPU (vertex array with positions and display colours, and
// its triangle indices), ready for Renderer::draw. Only what display needs is uploaded: normals and
// physical radiosity stay on disk. Move-only; create and destroy it with its GL context current.
#pragma once

#include "walkrad/formats/chunk.h"

namespace walkrad {

class GpuMesh {
 public:
  // Throws std::invalid_argument when colours do not match positions one to one.
  explicit GpuMesh(const ChunkMesh& mesh);
  ~GpuMesh();
  GpuMesh(GpuMesh&& other) noexcept;
  GpuMesh& operator=(GpuMesh&& other) noexcept;
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;

  unsigned vertex_array() const { return vertex_array_; }
  int index_count() const { return index_count_; }

 private:
  void release();

  unsigned vertex_array_ = 0, positions_ = 0, colors_ = 0, indices_ = 0;  // GL object names
  int index_count_ = 0;
};

}  // namespace walkrad
