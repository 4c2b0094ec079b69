// Reads a glTF 2.0 scene (.gltf or .glb) into the plain scene arrays (scene.h):
// - triangle primitives of every mesh under the default scene's node transforms (TRS or matrix);
//   pairs of consecutive triangles that form a planar convex quad are merged into one quad;
// - diffuse reflectance = baseColorFactor × the average of baseColorTexture (when present), capped at
//   0.99 with a warning, except a channel of exactly 1 stated by an untextured baseColorFactor, kept
//   with a warning (the bake refuses a closed scene where nothing absorbs);
// - emission E = π × emissiveFactor × KHR_materials_emissive_strength (glTF emission is radiance);
// - camera nodes (perspective) become viewpoints;
// - lights: KHR_lights_punctual (point, spot) and EXT_lights_ies luminaires (profiles by uri, data
//   URI or bufferView; multiplier, color; TILT=INCLUDE factors at the node's tilt from straight down, −Y).
// Zero-area triangles are dropped and counted. Bad input throws InputError naming file and place.
#pragma once

#include <string>

#include "walkrad/formats/scene.h"
#include "walkrad/formats/scene_reader.h"  // read_scene (by extension), declared here before

namespace walkrad {

// input_folder: where the files it refers to (buffers, images, IES profiles) may lie; empty: the
// file's own folder. A reference outside it is refused (InputError, kExitBadInput) before it is opened.
Scene read_gltf(const std::string& path, const std::string& input_folder = {});

}  // namespace walkrad
