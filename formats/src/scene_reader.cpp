// read_scene (scene_reader.h): dispatch by file extension.
#include "walkrad/formats/scene_reader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "walkrad/formats/error.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/mgf_reader.h"

namespace walkrad {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

bool is_mgf(const std::string& path) { return lower_extension(path) == ".mgf"; }

Scene read_scene(const std::string& path, const std::string& input_folder, int mgf_sides) {
  const std::string ext = lower_extension(path);
  if (ext == ".gltf" || ext == ".glb") return read_gltf(path, input_folder);
  if (ext == ".mgf") {
    MgfOptions options;
    options.input_folder = input_folder;
    options.default_sides = mgf_sides;
    return read_mgf(path, options);
  }
  throw InputError(path, "", "unknown scene format '" + ext + "' (walkrad reads .gltf, .glb and .mgf)", kExitBadInput);
}

}  // namespace walkrad
