// Writes a Draco-compressed chunk (KHR_draco_mesh_compression) as a seed for the chunk fuzz target,
// so that the fuzzer starts inside Draco's decoder (walkrad itself writes no Draco chunks yet).
// Built with WALKRAD_FUZZ (build-fuzz/tests/fuzz/walkrad_make_draco_seed OUT.glb).
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <nlohmann/json.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.glb\n", argv[0]);
    return 2;
  }
  // A unit quad in z = 0: two triangles, a normal, a colour per corner.
  const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const float n[3] = {0, 0, 1}, c[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  const int faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(2);
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nor = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const int col = builder.AddAttribute(draco::GeometryAttribute::COLOR, 3, draco::DT_FLOAT32);
  for (int f = 0; f < 2; ++f) {
    const draco::FaceIndex fi(f);
    builder.SetAttributeValuesForFace(pos, fi, p[faces[f][0]], p[faces[f][1]], p[faces[f][2]]);
    builder.SetAttributeValuesForFace(nor, fi, n, n, n);
    builder.SetAttributeValuesForFace(col, fi, c[faces[f][0]], c[faces[f][1]], c[faces[f][2]]);
  }
  std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  draco::Encoder encoder;
  draco::EncoderBuffer buffer;
  if (!mesh || !encoder.EncodeMeshToBuffer(*mesh, &buffer).ok()) {
    std::fprintf(stderr, "draco encoding failed\n");
    return 1;
  }
  std::string bin(buffer.data(), buffer.size());
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  const unsigned points = mesh->num_points();
  auto id = [&](int a) { return mesh->attribute(a)->unique_id(); };
  nlohmann::json doc = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_draco_mesh_compression"}},
      {"extensionsRequired", {"KHR_draco_mesh_compression"}},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"COLOR_0", 2}}}, {"indices", 3},
                                    {"extensions", {{"KHR_draco_mesh_compression",
                                                     {{"bufferView", 0},
                                                      {"attributes", {{"POSITION", id(pos)}, {"NORMAL", id(nor)}, {"COLOR_0", id(col)}}}}}}}}}}}}},
      {"accessors", {{{"componentType", 5126}, {"count", points}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                     {{"componentType", 5126}, {"count", points}, {"type", "VEC3"}},
                     {{"componentType", 5126}, {"count", points}, {"type", "VEC3"}},
                     {{"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", buffer.size()}}}},
      {"buffers", {{{"byteLength", bin.size()}}}},
  };
  std::string json = doc.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  auto u32 = [](std::string& s, uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); };
  std::string glb;
  u32(glb, 0x46546C67);
  u32(glb, 2);
  u32(glb, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  u32(glb, uint32_t(json.size()));
  u32(glb, 0x4E4F534A);
  glb += json;
  u32(glb, uint32_t(bin.size()));
  u32(glb, 0x004E4942);
  glb += bin;
  std::ofstream(argv[1], std::ios::binary).write(glb.data(), std::streamsize(glb.size()));
  std::printf("wrote %s: %u points, %zu bytes of Draco\n", argv[1], points, buffer.size());
  return 0;
}
