// Textured reflectance and emission per element. A material's reflectance and emission are
// its factors times its textures' averages; an element of a polygon with texture coordinates takes
// the textures' mean over its own area instead: the mean of 8 × 8 stratified points of the element,
// mapped to (u, v) by the polygon's affine map and sampled bilinearly. Only when the scene has such
// textures (effect plan "textures"); reflectance then stays at most 0.99 and ρ + τ at most 1.
#pragma once

#include "walkrad/formats/scene.h"

namespace walkrad {

struct SurfaceColour {
  Vec3 reflectance, emission;
};

// The element's reflectance and emission (its material's where it has no texture or no map).
SurfaceColour element_colour(const Scene& scene, const Polygon& element);

// Whether some polygon has texture coordinates and a material with a texture.
bool has_textures(const Scene& scene);

}  // namespace walkrad
