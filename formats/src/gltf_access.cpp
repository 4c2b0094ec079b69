#include "gltf_access.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "gltf_draco_check.h"
#include "input_limits.h"
#include "walkrad/formats/error.h"

#include <stb_image.h>

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

bool append_uvs(const tinygltf::Model& m, int accessor, std::vector<float>& out, const std::string& file) {
  const std::string place = "accessors[" + std::to_string(accessor) + "] (TEXCOORD)";
  if (accessor < 0 || accessor >= int(m.accessors.size())) throw InputError(file, place, "no such accessor");
  const tinygltf::Accessor& a = m.accessors[accessor];
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || a.type != TINYGLTF_TYPE_VEC2) return false;
  const View v = resolve(m, accessor, sizeof(float) * 2, file, place);
  const size_t base = out.size();
  out.resize(base + v.count * 2);
  for (size_t i = 0; i < v.count; ++i) std::memcpy(&out[base + i * 2], v.data + i * v.stride, sizeof(float) * 2);
  for (size_t i = base; i < out.size(); ++i)
    if (!std::isfinite(out[i])) throw InputError(file, place, "texture coordinate " + std::to_string((i - base) / 2) + " is not finite");
  return true;
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

namespace {

constexpr uint32_t kGlbMagic = 0x46546C67, kGlbJson = 0x4E4F534A, kGlbBin = 0x004E4942;
constexpr uint64_t kMaxImagePixels = uint64_t(1) << 26;  // 8192 × 8192: decoded before it is averaged

uint32_t u32(const std::vector<unsigned char>& b, size_t at) {
  return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}

// The GLB layout (glTF 2.0 §4.4) checked against the real file size before tinygltf reads a length
// from it: header, a JSON chunk, an optional BIN chunk, nothing past the declared length.
// Returns the JSON chunk's span.
std::pair<size_t, size_t> check_glb(const std::vector<unsigned char>& b, const std::string& file) {
  const size_t size = b.size();
  if (size < 20) throw InputError(file, "GLB header", "file of " + std::to_string(size) + " bytes is shorter than a GLB header and chunk header (20)");
  if (u32(b, 0) != kGlbMagic) throw InputError(file, "GLB header", "magic is not \"glTF\"");
  if (u32(b, 4) != 2) throw InputError(file, "GLB header", "version " + std::to_string(u32(b, 4)) + " (walkrad reads GLB version 2)", kExitMissingFeature);
  if (u32(b, 8) != size)
    throw InputError(file, "GLB header", "declared length " + std::to_string(u32(b, 8)) + " differs from the file size " + std::to_string(size));
  const uint64_t json_length = u32(b, 12);
  if (u32(b, 16) != kGlbJson) throw InputError(file, "GLB chunk 0", "the first chunk is not JSON");
  if (json_length == 0 || 20 + json_length > size)
    throw InputError(file, "GLB chunk 0", "JSON length " + std::to_string(json_length) + " does not fit in the file (" + std::to_string(size) + " bytes)");
  const uint64_t rest = size - 20 - json_length;
  if (rest > 0) {
    if (rest < 8) throw InputError(file, "GLB chunk 1", "truncated chunk header");
    const uint64_t bin_length = u32(b, size_t(20 + json_length));
    if (u32(b, size_t(24 + json_length)) != kGlbBin) throw InputError(file, "GLB chunk 1", "the second chunk is not BIN");
    if (bin_length + 8 > rest)
      throw InputError(file, "GLB chunk 1", "BIN length " + std::to_string(bin_length) + " exceeds the " + std::to_string(rest - 8) + " bytes left in the file");
  }
  return {20, size_t(json_length)};
}

// What tinygltf's file callbacks are handed: the glTF file (for refusals), its input folder, and whether
// the last path asked about lay inside it but did not exist.
struct Resources {
  const std::string& file;
  std::string folder;
  bool missing = false;
};

// tinygltf asks whether a buffer's or image's file exists before reading it, at the uri joined to the
// glTF's folder and then, where that does not exist, joined to the working directory. A path outside
// the input folder is refused here, before anything opens it; the working directory's, which only
// follows a missing file, is not looked at (tinygltf then says the file is not found).
bool resource_exists(const std::string& path, void* resources) {
  Resources& r = *static_cast<Resources*>(resources);
  const std::string why = input_limits::outside(path, r.folder);
  if (!why.empty()) {
    if (r.missing) return false;
    throw InputError(r.file, "resource '" + path + "'", why);
  }
  std::error_code ec;
  r.missing = !std::filesystem::exists(path, ec);
  return !r.missing;
}

// tinygltf's file reads (external buffers and images) with the same rules as the scene file.
// A refusal names the glTF file and the resource's path.
bool read_resource(std::vector<unsigned char>* out, std::string*, const std::string& path, void* resources) {
  const Resources& r = *static_cast<const Resources*>(resources);
  const std::string why = input_limits::outside(path, r.folder);
  if (!why.empty()) throw InputError(r.file, "resource '" + path + "'", why);
  try {
    *out = input_limits::read_file(path, input_limits::kMaxBinaryBytes, "file");
  } catch (const InputError& e) {
    throw InputError(r.file, "resource '" + path + "'", e.message(), e.code());
  }
  return true;
}

// Images are decoded to be averaged: refuse sizes whose decoding would need gigabytes.
bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int w, int h,
                const unsigned char* bytes, int size, void* file) {
  int x = 0, y = 0, comp = 0;
  if (stbi_info_from_memory(bytes, size, &x, &y, &comp) && uint64_t(x) * uint64_t(y) > kMaxImagePixels)
    throw InputError(*static_cast<const std::string*>(file), "images[" + std::to_string(index) + "]",
                     std::to_string(x) + " × " + std::to_string(y) + " pixels exceed the limit of " +
                     std::to_string(kMaxImagePixels) + " pixels", kExitLimitReached);
  return tinygltf::LoadImageData(image, index, err, warn, w, h, bytes, size, nullptr);
}

}  // namespace

tinygltf::Model load(const std::string& path, bool load_images, const std::string& folder) {
  const bool binary = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  const std::vector<unsigned char> bytes =
      input_limits::read_file(path, binary ? input_limits::kMaxBinaryBytes : input_limits::kMaxJsonBytes, "glTF file");
  const auto json = binary ? check_glb(bytes, path) : std::pair<size_t, size_t>{0, bytes.size()};
  input_limits::check_json_depth(reinterpret_cast<const char*>(bytes.data()) + json.first, json.second, path);
  const size_t bin_at = json.first + json.second + 8;  // a GLB's BIN chunk data, when there is one
  const bool has_bin = binary && bin_at <= bytes.size();
  check_draco(reinterpret_cast<const char*>(bytes.data()) + json.first, json.second, has_bin ? bytes.data() + bin_at : nullptr,
              has_bin ? std::min<size_t>(bytes.size() - bin_at, u32(bytes, bin_at - 8)) : 0, path);

  tinygltf::TinyGLTF loader;
  Resources resources{path, input_limits::input_folder(path, folder)};
  loader.SetFsCallbacks({&resource_exists, &tinygltf::ExpandFilePath, &read_resource, &tinygltf::WriteWholeFile, &resources});
  if (!load_images)
    loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) { return true; }, nullptr);
  else
    loader.SetImageLoader(&load_image, const_cast<std::string*>(&path));
  tinygltf::Model model;
  std::string err, warn;
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir)
                         : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                                      unsigned(bytes.size()), base_dir);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw InputError(path, "", err.empty() ? "not a readable glTF file" : "invalid glTF: " + err);
  }
  return model;
}

}  // namespace walkrad::gltf_access
