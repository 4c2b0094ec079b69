#include "draco_encode.h"

#include <draco/compression/decode.h>
#include <draco/compression/expert_encode.h>
#include <draco/mesh/mesh.h>

#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

int add_vec3(draco::Mesh& dm, draco::GeometryAttribute::Type type, const std::vector<float>& data) {
  const size_t n = data.size() / 3;
  draco::GeometryAttribute ga;
  ga.Init(type, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  const int id = dm.AddAttribute(ga, /*identity_mapping=*/true, uint32_t(n));
  for (size_t i = 0; i < n; ++i) dm.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)), &data[3 * i]);
  return id;
}

void quantise(draco::ExpertEncoder& enc, int id, const QuantGrid& g) {
  enc.SetAttributeExplicitQuantization(id, g.bits, 3, g.origin, g.range);
}

}  // namespace

DracoChunk draco_encode(const ChunkMesh& mesh, const ChunkEncoding& e, const std::string& path) {
  draco::Mesh dm;
  dm.set_num_points(uint32_t(mesh.vertex_count()));
  const int pos = add_vec3(dm, draco::GeometryAttribute::POSITION, mesh.positions);
  const int nrm = mesh.normals.empty() ? -1 : add_vec3(dm, draco::GeometryAttribute::NORMAL, mesh.normals);
  const int col = add_vec3(dm, draco::GeometryAttribute::COLOR, mesh.colors);
  const int rad = add_vec3(dm, draco::GeometryAttribute::GENERIC, mesh.radiosity);
  for (size_t t = 0; t < mesh.triangle_count(); ++t)
    dm.AddFace({draco::PointIndex(mesh.indices[3 * t]), draco::PointIndex(mesh.indices[3 * t + 1]),
                draco::PointIndex(mesh.indices[3 * t + 2])});

  draco::ExpertEncoder enc(dm);
  enc.SetSpeedOptions(e.speed, e.speed);
  quantise(enc, pos, e.position);
  if (nrm >= 0) enc.SetAttributeQuantization(nrm, e.normal_bits);
  quantise(enc, col, e.color);
  quantise(enc, rad, e.radiosity);
  draco::EncoderBuffer buffer;
  const draco::Status status = enc.EncodeToBuffer(&buffer);
  if (!status.ok()) throw OutputError(path + ": Draco could not encode the chunk: " + status.error_msg_string());

  DracoChunk out;
  out.bytes.assign(buffer.data(), buffer.data() + buffer.size());
  out.position_id = int(dm.attribute(pos)->unique_id());
  out.normal_id = nrm >= 0 ? int(dm.attribute(nrm)->unique_id()) : -1;
  out.color_id = int(dm.attribute(col)->unique_id());
  out.radiosity_id = int(dm.attribute(rad)->unique_id());

  // The decoder's view: glTF accessors must state its counts and POSITION's bounds.
  draco::DecoderBuffer in;
  in.Init(buffer.data(), buffer.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&in);
  if (!decoded.ok()) throw OutputError(path + ": Draco cannot decode what it encoded: " + decoded.status().error_msg_string());
  const draco::Mesh& back = *decoded.value();
  out.vertices = back.num_points();
  out.triangles = back.num_faces();
  const draco::PointAttribute* p = back.GetAttributeByUniqueId(uint32_t(out.position_id));
  for (uint32_t i = 0; i < back.num_points(); ++i) {
    float v[3];
    p->GetMappedValue(draco::PointIndex(i), v);
    out.bounds.extend(Vec3(v[0], v[1], v[2]));
  }
  return out;
}

}  // namespace walkrad
