// Irradiance from the sky (sky.h) at a surface point, through whatever openings the scene leaves:
//   E(x) = ∫_H L(ω) V(x, ω) cos θ dω,
// split by which of the scene's openings (openings.h; RayScene::openings) a direction crosses first.
// Through each opening in front of the point and seen from it, the integral over the opening's area,
//   ∫_P L V cos θx cos θy / r² dA  =  π F(x → P) ⟨L V⟩,
// F by the contour formula and ⟨L V⟩ the kernel-weighted mean over stratified points of P: exact for a
// uniform sky seen whole through a window, however small the window looks from the point. Every other
// direction (the open sky, openings not found or not chosen) is the hemisphere's:
//   π ∫_[0,1)² L(ω(a, b)) V(x, ω(a, b)) da db,
// with ω(a, b) the cosine-weighted map of the hemisphere about n (sin θ = √a, φ = 2πb), so that every
// cell of the unit square carries the same share of cos θ dω. The square is cut into base × base cells,
// one ray through each cell's centre; a cell whose value L·V differs from a neighbour's by more than
// kSkyContrast of the sky's mean luminance is cut in four, level after level, up to `levels` times: the
// rays gather along the edges of what the point sees of the sky (a window's frame, the horizon, the
// sun's glow in a clear sky) and the sky's open parts take one ray per coarse cell. With a window of
// an opening missed by the finder the answer is then L·π·F(x → opening) to within the finest cells that
// its outline crosses (exact for a cell wholly in or out). A level stops adding rays past `budget` (a tree's
// canopy): what it has not cut keeps its coarser value. Directions below the horizon of an analytic sky
// carry nothing and cast no ray. A fixed pattern in the frame of n (sampling.h frame): deterministic.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

struct SkyPattern {
  int base = 16;         // cells per side of the first level
  int levels = 3;        // times a cell may be cut in four
  int budget = 4096;     // the hemisphere's rays at most, whatever the level
  int opening_side = 8;  // side × side points of each opening's triangle
};
inline constexpr SkyPattern kSkyAtPoints{16, 3, 4096, 8};   // an output vertex: finest cells 1/16384 of the hemisphere
inline constexpr SkyPattern kSkyOverElements{8, 2, 512, 3};  // each of an element's 4 × 4 points (refinement)
inline constexpr double kSkyContrast = 0.05;

// E(x) for unit normal n; rays from `from` (x lifted off its surface) to past the scene, nullptr: no
// occluders. rays_cast counts the rays.
Vec3 sky_irradiance(const Sky& sky, const Vec3& n, const Vec3& from, const RayScene* rays, const SkyPattern& pattern,
                    uint64_t& rays_cast);


// The luminance the sky can pour on the polygons, Σ A π L̄ (1 + n·up) / 2 (L̄ its mean luminance; a
// tilted surface sees that share of an upper hemisphere; an image's whole sphere: Σ A π L̄): the scale of
// what the sky lights, for the error's white, as directional_power is for the sun.
double sky_power(const Sky& sky, const std::vector<Polygon>& polygons);

}  // namespace walkrad
