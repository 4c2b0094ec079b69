// GltfIesLights (gltf_ies.h): EXT_lights_ies profiles and their node instances.
#include "gltf_ies.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "input_limits.h"
#include "walkrad/formats/error.h"

namespace walkrad {

namespace {
constexpr const char* kIesMime = "application/x-ies-lm-63";
}  // namespace

namespace {
// A relative URI's path as a file name: %XX escapes decoded (glTF 2.0 §2.8: "my%20lamp.ies").
std::string uri_path(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}
}  // namespace

std::shared_ptr<const IesProfile> GltfIesLights::profile(int index) {
  const auto ext = model_.extensions.find("EXT_lights_ies");
  const tinygltf::Value* lights = ext != model_.extensions.end() && ext->second.Has("lights") ? &ext->second.Get("lights") : nullptr;
  if (!lights || !lights->IsArray() || index < 0 || size_t(index) >= lights->ArrayLen())
    throw InputError(file_, "extensions.EXT_lights_ies.lights", "light profile " + std::to_string(index) + " does not exist");
  if (profiles_.size() < lights->ArrayLen()) profiles_.resize(lights->ArrayLen());
  if (profiles_[size_t(index)]) return profiles_[size_t(index)];
  const std::string place = "extensions.EXT_lights_ies.lights[" + std::to_string(index) + "]";
  const tinygltf::Value& p = lights->Get(index);
  std::vector<unsigned char> bytes;
  if (p.Has("uri") && p.Get("uri").IsString()) {
    const std::string uri = p.Get("uri").Get<std::string>();
    const size_t comma = uri.find(";base64,");
    if (uri.rfind("data:", 0) == 0) {
      // tinygltf decodes the data URIs of buffers and images only: the payload is given to it as one.
      std::string mime;
      if (comma == std::string::npos ||
          !tinygltf::DecodeDataURI(&bytes, mime, "data:application/octet-stream;base64," + uri.substr(comma + 8), 0, false))
        throw InputError(file_, place, "the data URI cannot be decoded (base64 expected)");
    } else {
      const std::string path = (std::filesystem::path(file_).parent_path() / uri_path(uri)).string();
      if (const std::string why = input_limits::outside(path, folder_); !why.empty()) throw InputError(file_, place, "'" + path + "' " + why);
      return profiles_[size_t(index)] = std::make_shared<const IesProfile>(read_ies(path));
    }
  } else if (p.Has("bufferView") && p.Get("bufferView").IsInt()) {
    if (!p.Has("mimeType") || !p.Get("mimeType").IsString() || p.Get("mimeType").Get<std::string>() != kIesMime)
      throw InputError(file_, place, std::string("a profile in a bufferView needs mimeType \"") + kIesMime + "\"");
    const int bv = p.Get("bufferView").GetNumberAsInt();
    if (bv < 0 || bv >= int(model_.bufferViews.size())) throw InputError(file_, place, "bufferView index out of range");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(bv)];
    if (view.buffer < 0 || view.buffer >= int(model_.buffers.size()) ||
        view.byteOffset + view.byteLength > model_.buffers[size_t(view.buffer)].data.size())
      throw InputError(file_, place, "bufferView " + std::to_string(bv) + " lies outside its buffer");
    const auto& data = model_.buffers[size_t(view.buffer)].data;
    bytes.assign(data.begin() + long(view.byteOffset), data.begin() + long(view.byteOffset + view.byteLength));
  } else {
    throw InputError(file_, place, "a light profile needs a uri or a bufferView");
  }
  // Embedded (a data URI or a bufferView): as read_ies's limit for files.
  if (bytes.size() > kMaxIesBytes)
    throw InputError(file_, place, "the profile exceeds " + std::to_string(kMaxIesBytes >> 20) + " MiB", kExitLimitReached);
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return profiles_[size_t(index)] = std::make_shared<const IesProfile>(parse_ies(text, file_ + " (" + place + ")"));
}

void GltfIesLights::add(int node, const Vec3& position, const Vec3& direction, const Vec3& up, Scene& scene) {
  const tinygltf::Node& n = model_.nodes[size_t(node)];
  const auto ext = n.extensions.find("EXT_lights_ies");
  if (ext == n.extensions.end() || !ext->second.IsObject()) return;
  const std::string place = "nodes[" + std::to_string(node) + "].extensions.EXT_lights_ies";
  const tinygltf::Value& e = ext->second;
  if (!e.Has("light") || !e.Get("light").IsInt()) throw InputError(file_, place, "'light' (a profile index) is required");
  PunctualLight l;
  l.type = PunctualLight::Type::ies;
  l.profile = profile(e.Get("light").GetNumberAsInt());
  double multiplier = 1;
  if (e.Has("multiplier")) {
    if (!e.Get("multiplier").IsNumber()) throw InputError(file_, place, "'multiplier' must be a number");
    multiplier = e.Get("multiplier").GetNumberAsDouble();
  }
  Vec3 colour(1, 1, 1);
  if (e.Has("color")) {
    const tinygltf::Value& c = e.Get("color");
    if (!c.IsArray() || c.ArrayLen() != 3 || !c.Get(0).IsNumber() || !c.Get(1).IsNumber() || !c.Get(2).IsNumber())
      throw InputError(file_, place, "'color' must be 3 numbers");
    colour = {c.Get(0).GetNumberAsDouble(), c.Get(1).GetNumberAsDouble(), c.Get(2).GetNumberAsDouble()};
  }
  if (!(multiplier >= 0) || !std::isfinite(multiplier) || !is_finite(colour) || std::min({colour.x, colour.y, colour.z}) < 0)
    throw InputError(file_, place, "multiplier and color must be finite and not negative");
  // The extension clamps colour to [0, 1].
  colour = {std::min(colour.x, 1.0), std::min(colour.y, 1.0), std::min(colour.z, 1.0)};
  l.name = !n.name.empty() ? n.name : "luminaire-" + std::to_string(node);
  l.position = position;
  if (!is_valid_vertex(position) || !(length(direction) > 0)) throw InputError(file_, place, "the light's node transform is degenerate");
  l.direction = normalize(direction);
  l.up = orthogonal_up(l.direction, up);  // orthogonal even under a sheared transform
  if (l.up == Vec3{}) throw InputError(file_, place, "the light's node transform is degenerate");
  l.intensity = colour * (multiplier * l.profile->tilt_factor(l.direction, {0, -1, 0}));
  scene.lights.push_back(l);
}

}  // namespace walkrad
