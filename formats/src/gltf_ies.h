// glTF EXT_lights_ies (Khronos vendor extension): the asset's light profiles
// (extensions.EXT_lights_ies.lights[], each an LM-63 file by uri, data URI or bufferView) and the
// nodes that place them (nodes[].extensions.EXT_lights_ies: light, multiplier, color).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "walkrad/formats/scene.h"

namespace walkrad {

class GltfIesLights {
 public:
  // folder: where a profile named by uri may lie (input_limits.h).
  GltfIesLights(const tinygltf::Model& model, const std::string& file, std::string folder)
      : model_(model), file_(file), folder_(std::move(folder)) {}

  // The node's luminaire appended to scene.lights, if the node has one. position, direction (−Z)
  // and up (+Y) are the node's world frame; the node's scale does not change the intensity.
  void add(int node, const Vec3& position, const Vec3& direction, const Vec3& up, Scene& scene);

 private:
  std::shared_ptr<const IesProfile> profile(int index);  // read once each

  const tinygltf::Model& model_;
  const std::string& file_;
  const std::string folder_;
  std::vector<std::shared_ptr<const IesProfile>> profiles_;
};

}  // namespace walkrad
