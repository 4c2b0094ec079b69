// A scene's openings: windows, doors, roof lights and gaps, found from the geometry alone. The polygons
// that lie in one plane (either facing) are united in that plane; where the union is not convex, what
// its convex hull holds beyond it (Clipper: hull − union) is an opening: a window is a hole in its wall's
// plane, a door a notch cut from the wall's bottom edge, a courtyard a hole in the roof's. Pieces
// thinner than kOpeningWidth of the scene's diagonal (the cracks of T-junctions) are dropped. The sky
// is sampled through them (sky_light.h): what the user would otherwise mark by hand as a "portal".
// Some are not openings to anything (the inside corner of an L-shaped floor, the gable above a low
// wall): sampled through, they show what lies behind them, which costs rays and changes nothing.
#pragma once

#include <vector>

#include "walkrad/formats/scene.h"

namespace walkrad {

inline constexpr double kOpeningWidth = 1e-4;

struct Opening {
  std::vector<Polygon> triangles;  // the opening, triangulated (counter-clockwise about `normal`)
  Vec3 normal;                     // its plane's (one of the two)
  double area = 0;
};

// In a deterministic order (by plane, then as Clipper returns them).
std::vector<Opening> find_openings(const Scene& scene);

}  // namespace walkrad
