// Input clean-up before solving: a polygon given twice (same corners, same facing; the MGF hospital
// holds 12,302 such copies among 24,923 faces) doubles that surface's area in every exchange and
// creates power (a row of form factors summing to 2). Copies are dropped and counted.
#pragma once

#include <cstdint>

#include "walkrad/formats/scene.h"

namespace walkrad {

// Keeps the first of every set of identical polygons (corners equal to 1e-9 of the scene's diagonal,
// in any order, with the same facing); returns how many were dropped.
uint64_t remove_duplicate_polygons(Scene& scene);

// Moves the polygons of clear glass (Material::is_clear_glass) from scene.polygons to scene.glass, in
// their order: they take no part in the solve, and rays cross them with the pane's transmittance
// (RayScene::transmittance). Returns how many moved.
uint64_t separate_clear_glass(Scene& scene);

}  // namespace walkrad
