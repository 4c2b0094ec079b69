#include "walkrad/output/chunk_optimizer.h"

#include <meshoptimizer.h>

namespace walkrad {

namespace {

void remap_vec3(std::vector<float>& data, const std::vector<unsigned>& remap, size_t vertices, size_t unique) {
  if (data.empty()) return;
  std::vector<float> out(unique * 3);
  meshopt_remapVertexBuffer(out.data(), data.data(), vertices, sizeof(float) * 3, remap.data());
  data = std::move(out);
}

}  // namespace

void optimize_chunk(ChunkMesh& m) {
  const size_t vertices = m.vertex_count(), indices = m.indices.size();
  if (indices == 0) return;
  unsigned* idx = m.indices.data();
  meshopt_optimizeVertexCache(idx, idx, indices, vertices);
  meshopt_optimizeOverdraw(idx, idx, indices, m.positions.data(), vertices, sizeof(float) * 3, 1.05f);
  std::vector<unsigned> remap(vertices);
  const size_t unique = meshopt_optimizeVertexFetchRemap(remap.data(), idx, indices, vertices);
  meshopt_remapIndexBuffer(idx, idx, indices, remap.data());
  remap_vec3(m.positions, remap, vertices, unique);
  remap_vec3(m.normals, remap, vertices, unique);
  remap_vec3(m.colors, remap, vertices, unique);
  remap_vec3(m.radiosity, remap, vertices, unique);
}

}  // namespace walkrad
