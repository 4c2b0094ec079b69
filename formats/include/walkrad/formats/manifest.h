// The bake folder's manifest.json: what a bake holds and how to play it (versioned schema).
// Written by the pipeline, read by the runtime and by `walkrad inspect` / `walkrad diff`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "walkrad/formats/scene.h"

namespace walkrad {

constexpr const char* kManifestFormat = "walkrad-bake";
constexpr int kManifestVersion = 1;

struct ChunkInfo {
  std::string file;  // relative to the bake folder, a plain file name
  Bounds bounds;
  uint64_t triangles = 0;
  uint64_t bytes = 0;
  // Per viewpoint of the manifest: the fraction of that viewpoint's image the chunk covers (0..1).
  // A runtime streams first what the viewpoints ahead will see.
  std::vector<float> importance;
};

struct Manifest {
  std::string tool;                  // "walkrad X.Y.Z"
  std::string scene_file;            // the scene as given to the bake
  std::string scene_hash;            // FNV-1a 64 of the scene file's bytes, hex
  Bounds bounds;                     // of the whole bake
  double exposure = 1.0;             // display colour = radiance (B/π) × exposure
  std::vector<ChunkInfo> chunks;
  std::vector<Viewpoint> viewpoints; // the walkthrough the bake was made for, frame by frame
  nlohmann::json settings = nlohmann::json::object();  // the bake settings, as given
  nlohmann::json effects = nlohmann::json::object();   // the effect plan: what was simulated and why
};

nlohmann::json manifest_to_json(const Manifest& m);
// Validates as it reads; throws InputError with the file and a JSON pointer to the fault.
Manifest manifest_from_json(const nlohmann::json& j, const std::string& file);
Manifest read_manifest(const std::string& path);

}  // namespace walkrad
