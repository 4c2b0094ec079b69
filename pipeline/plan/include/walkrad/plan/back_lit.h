// Light that meets the back of one-sided polygons: a polygon absorbs what reaches it from behind (as
// RenderPark and the reference tracer read MGF), so a scene whose surfaces turn their backs to the
// lights, a room of slabs whose faces point into the slabs, say, read one-sided where its author meant
// two-sided, loses its light at the first bounce and shows black. The bake warns (the light's share and
// the materials that take it) before it solves: such a scene is what the file says, but rarely what
// its author meant.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

struct BackLight {
  double share = 0;  // of the emitted power (luminance), what first meets a back face
  // (material, share of the emitted power), largest first; a "… (covered)" copy (contact_split.h) counted
  // as the material it copies
  std::vector<std::pair<uint32_t, double>> materials;
  uint64_t rays = 0;
};

// kBackLitRays rays in all, each light taking its share of the power (luminance) in rays: from the
// emitting polygons' fronts, cosine-distributed; from punctual lights over the sphere (a spot's over
// its cone). Deterministic.
inline constexpr uint64_t kBackLitRays = 16384;
BackLight light_on_back_faces(const Scene& scene, const RayScene& rays);

// Above this share the bake warns (back_lit_warning); a closed room of two-sided walls loses none.
inline constexpr double kBackLitWarning = 0.5;
// "62% of the light emitted first meets the back of one-sided polygons (floor 31%, ...)", with the MGF or
// glTF way to say two-sided as scene.source is read: empty below kBackLitWarning.
std::string back_lit_warning(const Scene& scene, const BackLight& b);

}  // namespace walkrad
