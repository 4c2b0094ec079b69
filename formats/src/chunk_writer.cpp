// write_chunk (chunk_writer.h), through tinygltf's writer; Draco payloads from draco_encode. The buffer is laid out deterministically
// (attributes in a fixed order, 4-byte aligned) so that equal meshes give byte-identical files.
#include "walkrad/formats/chunk_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <tiny_gltf.h>

#include "draco_encode.h"
#include "gltf_build.h"
#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

// Bits for values spread over `range` with error at most `tolerance`: (2^bits − 1) steps of ≤ 2·tolerance.
int bits_for(double range, double tolerance) {
  if (!(range > 0) || !(tolerance > 0)) return 1;
  return std::clamp(int(std::ceil(std::log2(range / (2 * tolerance) + 1))), 1, 30);
}

// An accessor that a Draco primitive decodes into: no bufferView, the decoded count.
int draco_accessor(tinygltf::Model& model, int type, int component, size_t count) {
  tinygltf::Accessor acc;
  acc.componentType = component;
  acc.type = type;
  acc.count = count;
  model.accessors.push_back(acc);
  return int(model.accessors.size()) - 1;
}

// Draco payload in the buffer, and the primitive's accessors and extension.
void add_draco_primitive(tinygltf::Model& model, tinygltf::Primitive& prim, const ChunkMesh& mesh,
                         const ChunkEncoding& encoding, const std::string& path) {
  const DracoChunk d = draco_encode(mesh, encoding, path);
  auto& buf = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buf.size();
  view.byteLength = d.bytes.size();
  buf.insert(buf.end(), d.bytes.begin(), d.bytes.end());
  while (buf.size() % 4) buf.push_back(0);
  model.bufferViews.push_back(view);

  const int vec3 = TINYGLTF_TYPE_VEC3, f32 = TINYGLTF_COMPONENT_TYPE_FLOAT;
  prim.attributes["POSITION"] = draco_accessor(model, vec3, f32, d.vertices);
  model.accessors.back().minValues = {d.bounds.lo.x, d.bounds.lo.y, d.bounds.lo.z};
  model.accessors.back().maxValues = {d.bounds.hi.x, d.bounds.hi.y, d.bounds.hi.z};
  tinygltf::Value::Object ids;
  ids["POSITION"] = tinygltf::Value(d.position_id);
  if (d.normal_id >= 0) {
    prim.attributes["NORMAL"] = draco_accessor(model, vec3, f32, d.vertices);
    ids["NORMAL"] = tinygltf::Value(d.normal_id);
  }
  prim.attributes["COLOR_0"] = draco_accessor(model, vec3, f32, d.vertices);
  ids["COLOR_0"] = tinygltf::Value(d.color_id);
  prim.attributes["_RADIOSITY"] = draco_accessor(model, vec3, f32, d.vertices);
  ids["_RADIOSITY"] = tinygltf::Value(d.radiosity_id);
  prim.indices = draco_accessor(model, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, 3 * d.triangles);
  tinygltf::Value::Object ext;
  ext["bufferView"] = tinygltf::Value(int(model.bufferViews.size()) - 1);
  ext["attributes"] = tinygltf::Value(ids);
  prim.extensions["KHR_draco_mesh_compression"] = tinygltf::Value(ext);
  model.extensionsUsed.push_back("KHR_draco_mesh_compression");
  model.extensionsRequired.push_back("KHR_draco_mesh_compression");
}

}  // namespace

ChunkEncoding draco_encoding(const Bounds& bounds, double position_tolerance, double radiosity_max,
                             double radiosity_tolerance) {
  ChunkEncoding e;
  e.draco = true;
  const Vec3 size = bounds.diagonal();
  const double extent = std::max({size.x, size.y, size.z, 1e-30});
  for (int k = 0; k < 3; ++k) e.position.origin[k] = float(bounds.lo[k]);
  // The range is rounded up to a float, so the grid covers the bounds.
  e.position.range = std::nextafter(float(extent), INFINITY);
  e.position.bits = bits_for(e.position.range, position_tolerance);
  e.color.range = 1;
  e.color.bits = bits_for(1.0, 0.5 / 255 / 12.92);
  e.radiosity.range = std::nextafter(float(std::max(radiosity_max, 1e-30)), INFINITY);
  e.radiosity.bits = bits_for(e.radiosity.range, radiosity_tolerance);
  return e;
}

uint64_t write_chunk(const std::string& path, const ChunkMesh& mesh, const ChunkEncoding& encoding) {
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
  if (encoding.draco) {
    add_draco_primitive(model, prim, mesh, encoding, path);
  } else {
    prim.attributes["POSITION"] = gltf_build::append_vec3(model, mesh.positions, true);
    if (!mesh.normals.empty()) prim.attributes["NORMAL"] = gltf_build::append_vec3(model, mesh.normals, false);
    prim.attributes["COLOR_0"] = gltf_build::append_vec3(model, mesh.colors, false);
    prim.attributes["_RADIOSITY"] = gltf_build::append_vec3(model, mesh.radiosity, false);
    prim.indices = gltf_build::append_indices(model, mesh.indices);
  }

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
