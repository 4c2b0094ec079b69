// write_chunk (chunk_writer.h), through tinygltf's writer. The buffer is laid out deterministically
// (attributes in a fixed order, 4-byte aligned) so that equal meshes give byte-identical files.
#include "walkrad/formats/chunk_writer.h"

#include <cstring>
#include <filesystem>

#include <tiny_gltf.h>

#include "gltf_build.h"
#include "walkrad/formats/error.h"

namespace walkrad {


uint64_t write_chunk(const std::string& path, const ChunkMesh& mesh) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "walkrad";
  model.buffers.resize(1);
  model.extensionsUsed = {"KHR_materials_unlit"};

  tinygltf::Material mat;
  mat.name = "baked";
  mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 1.0;
  mat.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
  model.materials.push_back(mat);

  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = 0;
  prim.attributes["POSITION"] = gltf_build::append_vec3(model, mesh.positions, true);
  if (!mesh.normals.empty())
    prim.attributes["NORMAL"] = gltf_build::append_vec3(model, mesh.normals, false);
  prim.attributes["COLOR_0"] = gltf_build::append_vec3(model, mesh.colors, false);
  prim.attributes["_RADIOSITY"] = gltf_build::append_vec3(model, mesh.radiosity, false);
  prim.indices = gltf_build::append_indices(model, mesh.indices);

  tinygltf::Mesh m;
  m.name = "radiosity";
  m.primitives.push_back(prim);
  model.meshes.push_back(m);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, path, /*embedImages=*/true, /*embedBuffers=*/true,
                                   /*prettyPrint=*/false, /*writeBinary=*/true))
    throw OutputError(path + ": cannot write glTF");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw OutputError(path + ": cannot read back the written file's size");
  return size;
}

}  // namespace walkrad
