#include "gltf_draco_check.h"

#include <algorithm>
#include <cstdint>

#include <draco/compression/decode.h>
#include <nlohmann/json.hpp>

#include "walkrad/formats/error.h"

namespace walkrad::gltf_access {

namespace {

using nlohmann::json;

// The element at index `i` of doc[key], when i is an integer in range.
const json* element(const json& doc, const char* key, const json& i) {
  if (!i.is_number_integer() || !doc.contains(key) || !doc[key].is_array()) return nullptr;
  const int64_t k = i.get<int64_t>();
  return k >= 0 && k < int64_t(doc[key].size()) ? &doc[key][size_t(k)] : nullptr;
}

bool valid_component_type(const json& accessor, bool index) {
  const json* t = accessor.is_object() && accessor.contains("componentType") ? &accessor["componentType"] : nullptr;
  if (!t || !t->is_number_integer()) return false;
  const int64_t c = t->get<int64_t>();
  return index ? (c == 5121 || c == 5123 || c == 5125) : (c == 5120 || c == 5121 || c == 5122 || c == 5123 || c == 5125 || c == 5126);
}

}  // namespace

void check_draco(const char* text, size_t size, const unsigned char* bin, size_t bin_size, const std::string& file) {
  static const char kName[] = "KHR_draco_mesh_compression";
  if (std::search(text, text + size, kName, kName + sizeof kName - 1) == text + size) return;
  json doc;
  try {
    doc = json::parse(text, text + size);
  } catch (const json::exception&) {
    return;  // tinygltf reports the syntax error
  }
  if (!doc.is_object() || !doc.contains("meshes") || !doc["meshes"].is_array()) return;
  for (size_t m = 0; m < doc["meshes"].size(); ++m) {
    const json& mesh = doc["meshes"][m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const json& prim = mesh["primitives"][p];
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
          !prim["extensions"].contains(kName))
        continue;
      const std::string place = "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]." + kName;
      const json& ext = prim["extensions"][kName];
      if (!ext.is_object() || !ext.contains("bufferView") || !ext.contains("attributes") || !ext["attributes"].is_object())
        throw InputError(file, place, "needs a bufferView and an attributes object");
      const json* view = element(doc, "bufferViews", ext["bufferView"]);
      if (!view || !view->is_object() || !view->contains("byteLength")) throw InputError(file, place, "bufferView does not exist");
      const json* buffer = element(doc, "buffers", view->value("buffer", json()));
      if (!buffer || !buffer->is_object()) throw InputError(file, place, "the bufferView's buffer does not exist");
      if (buffer->contains("uri") || &(*buffer) != &doc["buffers"][0])
        throw InputError(file, place, "Draco data outside the GLB's BIN chunk is not supported", kExitMissingFeature);
      const json& offset_j = view->value("byteOffset", json(0)), &length_j = (*view)["byteLength"];
      if (!offset_j.is_number_unsigned() && !offset_j.is_number_integer()) throw InputError(file, place, "bad byteOffset");
      if (!length_j.is_number_unsigned() && !length_j.is_number_integer()) throw InputError(file, place, "bad byteLength");
      const int64_t offset = offset_j.get<int64_t>(), length = length_j.get<int64_t>();
      if (offset < 0 || length < 0 || uint64_t(offset) + uint64_t(length) > bin_size)
        throw InputError(file, place, "the Draco bufferView lies outside the BIN chunk");
      // tinygltf keeps only the buffer's declared byteLength of the BIN chunk and hands Draco the
      // view without checking it against that (a fuzzing finding: a view one byte past the buffer).
      const json& declared = buffer->value("byteLength", json());
      if (!declared.is_number_integer() || declared.get<int64_t>() < 0 ||
          uint64_t(offset) + uint64_t(length) > uint64_t(declared.get<int64_t>()))
        throw InputError(file, place, "the Draco bufferView lies outside its buffer's byteLength");
      if (prim.contains("indices")) {
        const json* acc = element(doc, "accessors", prim["indices"]);
        if (!acc || !valid_component_type(*acc, true)) throw InputError(file, place, "indices: no such accessor, or not unsigned");
      }
      draco::DecoderBuffer data;
      data.Init(reinterpret_cast<const char*>(bin + offset), size_t(length));
      draco::Decoder decoder;
      auto decoded = decoder.DecodeMeshFromBuffer(&data);
      if (!decoded.ok()) throw InputError(file, place, std::string("Draco data does not decode: ") + decoded.status().error_msg());
      const draco::Mesh& dm = *decoded.value();
      for (const auto& [name, id] : ext["attributes"].items()) {
        if (!id.is_number_integer()) throw InputError(file, place + "/attributes/" + name, "expected an integer id");
        const int64_t uid = id.get<int64_t>();
        if (uid < 0 || uid > INT32_MAX || !dm.GetAttributeByUniqueId(uint32_t(uid)))
          throw InputError(file, place + "/attributes/" + name, "no Draco attribute with id " + std::to_string(uid));
        const draco::PointAttribute& attribute = *dm.GetAttributeByUniqueId(uint32_t(uid));
        // At most 4 components (glTF's largest vector): tinygltf converts each point into a 4-value
        // array on the stack (a fuzzing finding: a NORMAL of 9 components overflowed it).
        if (attribute.num_components() < 1 || attribute.num_components() > 4)
          throw InputError(file, place + "/attributes/" + name,
                           "the Draco attribute has " + std::to_string(int(attribute.num_components())) +
                               " components (glTF's vectors have 1 to 4)");
        // glTF's component types only: tinygltf converts through Draco's templates, which read a bool
        // attribute's bytes as bool (a fuzzing finding: undefined behaviour on the byte 128).
        switch (attribute.data_type()) {
          case draco::DT_INT8: case draco::DT_UINT8: case draco::DT_INT16: case draco::DT_UINT16:
          case draco::DT_UINT32: case draco::DT_FLOAT32:
            break;
          default:
            throw InputError(file, place + "/attributes/" + name, "the Draco attribute's data type is not one glTF allows");
        }
        const json* attrs = prim.contains("attributes") && prim["attributes"].is_object() ? &prim["attributes"] : nullptr;
        const json* acc = attrs && attrs->contains(name) ? element(doc, "accessors", (*attrs)[name]) : nullptr;
        if (!acc || !valid_component_type(*acc, false))
          throw InputError(file, place + "/attributes/" + name, "the primitive has no valid accessor for it");
      }
    }
  }
}

}  // namespace walkrad::gltf_access
