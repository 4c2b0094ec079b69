// read_chunk: a bake chunk (.glb) back into plain arrays, through tinygltf (Draco decoded there).
#include "gltf_access.h"
#include "walkrad/formats/chunk.h"
#include "walkrad/formats/error.h"

namespace walkrad {

Bounds ChunkMesh::bounds() const {
  Bounds b;
  for (size_t i = 0; i + 2 < positions.size(); i += 3) b.extend(Vec3(positions[i], positions[i + 1], positions[i + 2]));
  return b;
}


ChunkMesh read_chunk(const std::string& path) {
  using namespace gltf_access;
  const tinygltf::Model model = load(path, /*load_images=*/false);

  ChunkMesh mesh;
  for (size_t mi = 0; mi < model.meshes.size(); ++mi) {
    for (const tinygltf::Primitive& prim : model.meshes[mi].primitives) {
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;
      const auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) throw InputError(path, "mesh " + std::to_string(mi), "primitive without POSITION");
      const uint32_t base = uint32_t(mesh.vertex_count());
      append_floats(model, pos->second, 3, mesh.positions, path, "POSITION");
      const size_t n = mesh.vertex_count() - base;
      auto attribute = [&](const char* name, std::vector<float>& out, float fill) {
        const auto it = prim.attributes.find(name);
        if (it != prim.attributes.end()) append_floats(model, it->second, 3, out, path, name);
        else out.resize(out.size() + 3 * n, fill);
        if (out.size() != mesh.positions.size()) throw InputError(path, std::string("attribute ") + name, "count differs from POSITION");
      };
      attribute("NORMAL", mesh.normals, 0.0f);
      attribute("COLOR_0", mesh.colors, 1.0f);
      attribute("_RADIOSITY", mesh.radiosity, 0.0f);
      if (prim.indices >= 0) {
        append_indices(model, prim.indices, base, mesh.indices, path);
      } else {
        for (uint32_t i = 0; i < n; ++i) mesh.indices.push_back(base + i);
      }
    }
  }
  if (mesh.indices.size() % 3) throw InputError(path, "indices", "count is not a multiple of 3");
  for (uint32_t i : mesh.indices)
    if (i >= mesh.vertex_count()) throw InputError(path, "indices", "index " + std::to_string(i) + " out of range");
  return mesh;
}

}  // namespace walkrad
