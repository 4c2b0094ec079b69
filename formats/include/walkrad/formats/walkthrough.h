// The walkthrough file: the viewpoints a bake is made for (JSON, versioned schema, strict: an
// unknown or mistyped field is an error, not a silent default). Two forms:
//
//   {"format": "walkrad-walkthrough", "version": 1,
//    "viewpoints": [{"name": "a", "position": [x,y,z], "target": [x,y,z], "up": [0,1,0],
//                    "yfov_deg": 40, "aspect": 1.5}, ...]}
//
//   {"format": "walkrad-walkthrough", "version": 1,
//    "path": {"frames": 120, "yfov_deg": 40, "aspect": 1.5,
//             "keyframes": [{"time": 0, "position": [...], "target": [...]}, ...]}}
//
// A path is sampled into `frames` viewpoints evenly in time, positions and targets interpolated by
// Catmull-Rom splines through the keyframes. "direction" may replace "target".
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "walkrad/formats/scene.h"

namespace walkrad {

constexpr const char* kWalkthroughFormat = "walkrad-walkthrough";
constexpr int kWalkthroughVersion = 1;
constexpr int kMaxWalkthroughFrames = 100000;  // a larger path is refused (a limit, not a bake)

std::vector<Viewpoint> walkthrough_from_json(const nlohmann::json& j, const std::string& file);
std::vector<Viewpoint> read_walkthrough(const std::string& path);

// Serialises viewpoints in the manifest's form (position, forward, up, yfov radians, aspect).
nlohmann::json viewpoint_to_json(const Viewpoint& v);
Viewpoint viewpoint_from_json(const nlohmann::json& j, const std::string& file, const std::string& pointer);

}  // namespace walkrad
