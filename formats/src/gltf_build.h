// Writing glTF buffers with tinygltf, shared by the chunk and scene writers: tightly packed,
// 4-byte aligned views in a fixed order, so equal inputs give byte-identical files.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <tiny_gltf.h>

namespace walkrad::gltf_build {

// Appends a tightly packed float VEC3 (or uint32 SCALAR) view + accessor; returns the accessor index.
template <typename T>
inline int append_accessor(tinygltf::Model& model, const std::vector<T>& data, int type, int component, int target,
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


// Float VEC3 data (positions get min/max, as glTF requires) and uint32 indices.
inline int append_vec3(tinygltf::Model& model, const std::vector<float>& data, bool with_bounds) {
  return append_accessor(model, data, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER,
                         with_bounds);
}
inline int append_indices(tinygltf::Model& model, const std::vector<uint32_t>& data) {
  return append_accessor(model, data, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                         TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, false);
}

}  // namespace walkrad::gltf_build
