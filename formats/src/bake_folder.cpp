#include "walkrad/formats/bake_folder.h"

namespace walkrad {

void append_mesh(ChunkMesh& a, const ChunkMesh& b) {
  const auto base = uint32_t(a.vertex_count());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
  a.colors.insert(a.colors.end(), b.colors.begin(), b.colors.end());
  a.radiosity.insert(a.radiosity.end(), b.radiosity.begin(), b.radiosity.end());
  for (uint32_t i : b.indices) a.indices.push_back(base + i);
}

ChunkMesh read_bake_mesh(const std::string& folder) {
  const Manifest m = read_manifest(folder + "/manifest.json");
  ChunkMesh all;
  for (const ChunkInfo& c : m.chunks) append_mesh(all, read_chunk(folder + "/" + c.file));
  return all;
}

}  // namespace walkrad
