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

}  // namespace walkrad
