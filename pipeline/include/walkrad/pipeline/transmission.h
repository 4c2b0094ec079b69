// Diffuse transmission (issue 10): a transmitting material (glTF KHR_materials_diffuse_transmission or
// KHR_materials_transmission, MGF td) lets light arriving on one side of a surface leave the other,
// as a lampshade or a curtain does. Polygons are one-sided here, so each transmitting polygon gets a
// twin: the same polygon facing the other way, with the same material. A leaf element of either side
// radiates B = E + ρ (H + D) + τ (H' + D'), where H' and D' are what the twin receives at the same
// place (two-sided radiosity with transmission: Rushmeier & Torrance 1990, §2). The hierarchical
// method only; the classic one ignores transmission and says so in its effect plan.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/pipeline/effect_plan.h"
#include "walkrad/pipeline/hierarchy.h"

namespace walkrad {

constexpr uint32_t kNoTwin = UINT32_MAX;

// Appends a reversed copy of every polygon whose material transmits; returns each polygon's twin
// (kNoTwin for none), the scene's polygons and the copies alike.
std::vector<uint32_t> add_transmission_twins(Scene& scene);

// What the twin side of a transmitting leaf receives over the same region (irradiance from links and
// punctual lights, H + D, as last solved): the twin's node at the leaf's place and depth, its leaves'
// area mean if the twin is finer there. Twins of one polygon split into the same regions, so each side
// passes on exactly what the other received (the energy audit closes).
Vec3 twin_received(const Hierarchy& h, const HNode& leaf, uint32_t twin_polygon);

// The effect-plan entry: on when a polygon's material transmits and the method is hierarchical;
// overrides as plan_effects' ("transmission" → "on" or "off").
Effect plan_transmission(const Scene& scene, const std::string& method, const std::map<std::string, std::string>& overrides);

}  // namespace walkrad
