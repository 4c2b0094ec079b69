// Diffuse transmission: a transmitting material (glTF KHR_materials_diffuse_transmission or
// KHR_materials_transmission, MGF td) lets light arriving on one side of a surface leave the other,
// as a lampshade or a curtain does. Each transmitting polygon has a twin facing the other way
// (walkrad/scene/transmission_twins.h). A leaf element of either side radiates B = E + ρ (H + D) + τ (H' + D'), where H' and D' are what the twin receives at the same
// place (two-sided radiosity with transmission: Rushmeier & Torrance 1990, §2). The hierarchical
// method only; the classic one ignores transmission and says so in its effect plan.
#pragma once

#include <cstdint>

#include "walkrad/formats/scene.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/scene/transmission_twins.h"

namespace walkrad {

// What the twin side of a transmitting leaf receives over the same region (irradiance from links and
// punctual lights, H + D, as last solved): the twin's node at the leaf's place and depth, its leaves'
// area mean if the twin is finer there. Twins of one polygon split into the same regions, so each side
// passes on exactly what the other received (the energy audit closes).
Vec3 twin_received(const Hierarchy& h, const HNode& leaf, uint32_t twin_polygon);
// The twin's node at leaf's place and depth (its deepest above that place where the twin is coarser).
uint32_t twin_node(const Hierarchy& h, const HNode& leaf, uint32_t twin_polygon);
// τ of an element's material.
Vec3 material_transmittance(const Hierarchy& h, const HNode& element);
// Its punctual lights' part alone (D'), as twin_received() takes it.
Vec3 twin_direct(const Hierarchy& h, const HNode& leaf, uint32_t twin_polygon);

}  // namespace walkrad
