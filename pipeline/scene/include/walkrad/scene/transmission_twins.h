// Diffuse transmission's twins: polygons are one-sided here, so each polygon whose material
// transmits (glTF KHR_materials_diffuse_transmission or KHR_materials_transmission, MGF td) gets a
// twin: the same polygon facing the other way, with the same material. The hierarchical method then
// passes light from one to the other (walkrad/hierarchical/transmission.h).
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/scene.h"

namespace walkrad {

constexpr uint32_t kNoTwin = UINT32_MAX;

// Appends a reversed copy of every polygon whose material transmits; returns each polygon's twin
// (kNoTwin for none), the scene's polygons and the copies alike.
std::vector<uint32_t> add_transmission_twins(Scene& scene);

}  // namespace walkrad
