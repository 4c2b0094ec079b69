#include "gltf_access.h"

#include <cstring>
#include <filesystem>

#include "walkrad/formats/error.h"

namespace walkrad::gltf_access {

namespace {

struct View {
  const unsigned char* data;
  size_t stride, count, element;
};

// Resolves accessor → bufferView → buffer and checks that count elements of `element` bytes fit.
View resolve(const tinygltf::Model& m, int accessor, size_t element, const std::string& file, const std::string& place) {
  if (accessor < 0 || accessor >= int(m.accessors.size())) throw InputError(file, place, "no such accessor");
  const tinygltf::Accessor& a = m.accessors[accessor];
  if (a.sparse.isSparse) throw InputError(file, place, "sparse accessors are not supported", kExitMissingFeature);
  if (a.bufferView < 0 || a.bufferView >= int(m.bufferViews.size())) throw InputError(file, place, "has no valid bufferView");
  const tinygltf::BufferView& bv = m.bufferViews[a.bufferView];
  if (bv.buffer < 0 || bv.buffer >= int(m.buffers.size())) throw InputError(file, place, "bufferView has no valid buffer");
  const auto& data = m.buffers[bv.buffer].data;
  const size_t stride = bv.byteStride ? bv.byteStride : element;
  const size_t start = bv.byteOffset + a.byteOffset;
  const size_t view_end = bv.byteOffset + bv.byteLength;
  if (a.count > 0) {
    // Overflow-safe: count is bounded by the view's length before it is multiplied.
    if (stride == 0 || a.count - 1 > view_end / stride) throw InputError(file, place, "count exceeds its bufferView");
    const size_t end = start + stride * (a.count - 1) + element;
    if (end > view_end || view_end > data.size()) throw InputError(file, place, "reads past the end of its buffer");
  }
  return {data.data() + start, stride, a.count, element};
}

}  // namespace

void append_floats(const tinygltf::Model& m, int accessor, int components, std::vector<float>& out,
                   const std::string& file, const std::string& name) {
  const std::string place = "accessors[" + std::to_string(accessor) + "] (" + name + ")";
  if (accessor < 0 || accessor >= int(m.accessors.size())) throw InputError(file, place, "no such accessor");
  const tinygltf::Accessor& a = m.accessors[accessor];
  const int have = a.type == TINYGLTF_TYPE_VEC4 ? 4 : (a.type == TINYGLTF_TYPE_VEC3 ? 3 : 0);
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || have < components)
    throw InputError(file, place, "expected float VEC" + std::to_string(components), kExitMissingFeature);
  const View v = resolve(m, accessor, sizeof(float) * have, file, place);
  const size_t base = out.size();
  out.resize(base + v.count * components);
  for (size_t i = 0; i < v.count; ++i) std::memcpy(&out[base + i * components], v.data + i * v.stride, sizeof(float) * components);
}

void append_indices(const tinygltf::Model& m, int accessor, uint32_t offset, std::vector<uint32_t>& out,
                    const std::string& file) {
  const std::string place = "accessors[" + std::to_string(accessor) + "] (indices)";
  if (accessor < 0 || accessor >= int(m.accessors.size())) throw InputError(file, place, "no such accessor");
  const tinygltf::Accessor& a = m.accessors[accessor];
  size_t size = 0;
  switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
    default: throw InputError(file, place, "indices must be unsigned byte, short or int");
  }
  if (a.type != TINYGLTF_TYPE_SCALAR) throw InputError(file, place, "indices must be SCALAR");
  const View v = resolve(m, accessor, size, file, place);
  out.reserve(out.size() + v.count);
  for (size_t i = 0; i < v.count; ++i) {
    const unsigned char* p = v.data + i * v.stride;
    uint32_t x = 0;
    if (size == 1) x = *p;
    else if (size == 2) { uint16_t s; std::memcpy(&s, p, 2); x = s; }
    else std::memcpy(&x, p, 4);
    out.push_back(x + offset);
  }
}

tinygltf::Model load(const std::string& path, bool load_images) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "", "cannot open file (missing or not a regular file)");
  tinygltf::TinyGLTF loader;
  if (!load_images)
    loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) { return true; }, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const bool binary = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                         : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw InputError(path, "", err.empty() ? "not a readable glTF file" : "invalid glTF: " + err);
  }
  return model;
}

}  // namespace walkrad::gltf_access
