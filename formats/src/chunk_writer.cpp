// write_chunk (chunk_writer.h), through tinygltf's writer. The buffer is laid out deterministically
// (attributes in a fixed order, 4-byte aligned) so that equal meshes give byte-identical files.
#include "walkrad/formats/chunk_writer.h"

#include <cstring>
#include <filesystem>

#include <tiny_gltf.h>

#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

// Appends a tightly packed float VEC3 (or uint32 SCALAR) view + accessor; returns the accessor index.
template <typename T>
int append_accessor(tinygltf::Model& model, const std::vector<T>& data, int type, int component, int target,
                    bool with_bounds) {
  auto& buf = model.buffers[0].data;
  const size_t offset = buf.size();
  buf.resize(offset + data.size() * sizeof(T));
  if (!data.empty()) std::memcpy(buf.data() + offset, data.data(), data.size() * sizeof(T));
  while (buf.size() % 4) buf.push_back(0);

  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = data.size() * sizeof(T);
  view.target = target;
  model.bufferViews.push_back(view);

  tinygltf::Accessor acc;
  acc.bufferView = int(model.bufferViews.size()) - 1;
  acc.componentType = component;
  acc.type = type;
  const size_t comps = type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
  acc.count = data.size() / comps;
  if (with_bounds) {
    acc.minValues.assign(comps, INFINITY);
    acc.maxValues.assign(comps, -INFINITY);
    for (size_t i = 0; i < data.size(); ++i) {
      acc.minValues[i % comps] = std::min(acc.minValues[i % comps], double(data[i]));
      acc.maxValues[i % comps] = std::max(acc.maxValues[i % comps], double(data[i]));
    }
  }
  model.accessors.push_back(acc);
  return int(model.accessors.size()) - 1;
}

}  // namespace

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
  prim.attributes["POSITION"] = append_accessor(model, mesh.positions, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                TINYGLTF_TARGET_ARRAY_BUFFER, true);
  if (!mesh.normals.empty())
    prim.attributes["NORMAL"] = append_accessor(model, mesh.normals, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                TINYGLTF_TARGET_ARRAY_BUFFER, false);
  prim.attributes["COLOR_0"] = append_accessor(model, mesh.colors, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                               TINYGLTF_TARGET_ARRAY_BUFFER, false);
  prim.attributes["_RADIOSITY"] = append_accessor(model, mesh.radiosity, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                  TINYGLTF_TARGET_ARRAY_BUFFER, false);
  prim.indices = append_accessor(model, mesh.indices, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                 TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, false);

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
