// write_scene_gltf: the plain scene arrays (scene.h) as a glTF 2.0 scene, for users who move on
// from MGF (`walkrad convert`). read_gltf gives back the same polygons (positions to float
// precision), materials and viewpoints:
// - one mesh and node per material; the node is translated to the centre of the mesh's bounds so
//   that float positions keep their precision in large scenes. A quad is written as two triangles
//   on its diagonal v0-v2, which read_gltf merges back; triangles that read_gltf could merge with a
//   neighbour are put in separate primitives.
// - material: baseColorFactor = reflectance, metallic 0, roughness 1; emission E (radiosity) as
//   radiance E/π = emissiveFactor × KHR_materials_emissive_strength (the extension only when E/π
//   exceeds 1 in some channel, with strength = the largest channel).
// - viewpoints as perspective camera nodes (glTF cameras look down their -Z with +Y up), near plane
//   1 cm, far plane twice the distance that takes in the whole scene.
// Formats write side: the runtime never links it.
#pragma once

#include <string>

#include "walkrad/formats/scene.h"

namespace walkrad {

// Writes .glb (binary) or .gltf (JSON with the buffer embedded) by the path's extension.
// Throws std::invalid_argument for another extension and OutputError when the file cannot be written.
void write_scene_gltf(const Scene& scene, const std::string& path);

}  // namespace walkrad
