// From the classic method's elements to a displayable mesh: the elements are the faces of the
// crack-free Gouraud mesh of surface_mesher.h.
#pragma once

#include <vector>

#include "walkrad/classic/subdivision.h"
#include "walkrad/output/surface_mesher.h"

namespace walkrad {

// radiosity: B per element. exposure: display colour = B/π × exposure, clamped to [0, 1] (what a
// display shows; lights saturate). _RADIOSITY keeps the unclamped physical value.
SurfaceMesh mesh_elements(const Subdivision& sub, const std::vector<Vec3>& radiosity, double exposure);

}  // namespace walkrad
