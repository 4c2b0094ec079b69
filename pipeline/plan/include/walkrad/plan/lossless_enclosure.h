// Light that cannot decay: a set of polygons that absorb nothing in some colour channel (ρ + τ = 1)
// and are closed among themselves (the light leaving any of them lands on another of them), with a
// light inside. Each bounce returns all of it, the Neumann series Σ (ρF)ᵏ E diverges there, and the
// sweeps could only raise its radiosity without end, however much the rest of the scene absorbs.
// channels_without_absorption + is_closed (effect_plan.h) find the case where the set is the whole scene.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

struct LosslessEnclosure {
  int channel = 0;                  // 0 red, 1 green, 2 blue
  std::vector<uint32_t> polygons;   // scene polygon indices, ascending
  std::vector<uint32_t> lights;     // the punctual lights inside (scene.lights indices)
  bool lit = false;                 // an emitting polygon or a punctual light inside
};

// The closed lossless sets, found by rays: from every polygon with ρ + τ ≥ 1 in a channel,
// kEnclosureRays cosine-distributed rays from its front (fewer where it has already shown a way
// out). A polygon leaks if a ray escapes, meets a back face (which absorbs) or a polygon that absorbs,
// or meets a polygon that leaks; the polygons left, grouped by the rays between them, are the
// enclosures. Punctual lights are inside one when all kEnclosureRays rays from them, spread over the
// sphere, meet its polygons' front faces. A hole that no ray finds (under about 1/kEnclosureRays of
// what a polygon sees) goes unseen. twins: each polygon's transmission twin (transmission_twins.h),
// through which a polygon with τ > 0 passes light on; empty where transmission is not simulated, and τ
// then counts as absorbed. Deterministic; only lossless polygons cast rays.
inline constexpr int kEnclosureRays = 64;
std::vector<LosslessEnclosure> find_lossless_enclosures(const Scene& scene, const RayScene& rays,
                                                        const std::vector<uint32_t>& twins = {});

// "3 polygons (material 'white'; MGF lines 12, 13, 14)": what a message names of an enclosure,
// at most `most` sources. The sources are MGF face lines or glTF mesh indices, as the file is.
std::string describe_polygons(const Scene& scene, const std::vector<uint32_t>& polygons, size_t most = 8);

}  // namespace walkrad
