// Direct light from punctual lights (glTF KHR_lights_punctual) and IES luminaires (EXT_lights_ies). A
// point, spot or luminaire is no surface, so no link can reach it: its irradiance is shot straight to
// the elements,
//   E(x) = I · max(0, n·ω) / r² · D(−ω) · window(r) · V(x, p),   ω = (p − x) / r,
// with D the light's distribution: 1 for a point, the extension's spot falloff (the square of a
// linear ramp in cos θ between the outer and the inner cone), or a luminaire's IES candela towards
// −ω in its own frame (ies.h, interpolated as LM-63 says); and, when a range is given, the window
// clamp(1 − (r / range)⁴, 0, 1). An element's
// irradiance is the mean over stratified points of its surface, one shadow ray (Embree) each; what
// it reflects, ρ·E, then travels through the links like emitted light (hierarchical and classic).
// A directional light (the sun) gives E(x) = E⊥ · max(0, n·ω) · V_sun(x), ω = −direction: V_sun the
// share of kSunRays shadow rays, towards a fixed stratified pattern of the sun's disc, that leave the
// scene unblocked (the penumbra: a uniform disc of the light's angular diameter; the cosine taken at
// the disc's centre, within (angular radius)²/2 of its mean over the disc).
// The sky (sky.h) gives what sky_irradiance (sky_light.h) finds through the scene's openings: at points
// with kSkyAtPoints, at each of an element's stratified points with the coarser kSkyOverElements.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

// The distribution D towards unit direction `out` (from the light): 1 for a point light, the spot
// falloff, or the IES profile's candela (the light's intensity is per candela).
double light_distribution(const PunctualLight& light, const Vec3& out);

// Shadow rays per point for a directional light: the penumbra in steps of 1/16 of the sun.
inline constexpr int kSunRays = 16;

// The range window at distance r (1 without a range).
double range_window(const PunctualLight& light, double r);

// What the light radiates, W per channel: 4π I for a point, I ∫ spot dΩ for a spot, I × the
// profile's flux for a luminaire (the range's window ignored: it depends on what stands where); for a
// directional light, what falls on the polygons facing it with nothing in the way, Σ E⊥ A max(0, n·ω),
// which needs the scene: directional_power (punctual_power gives 0 for it, and for the sky: sky_power).
Vec3 punctual_power(const PunctualLight& light);
Vec3 directional_power(const PunctualLight& light, const std::vector<Polygon>& polygons);

// Irradiance at a surface point from every light; rays: occluders (nullptr: none). rays_cast counts.
// The shadow rays leave from origin when given (a point at a polygon's edge lies on its neighbour's
// plane: the caller moves it in), else from x lifted off its surface.
Vec3 point_irradiance(const Vec3& x, const Vec3& normal, const std::vector<PunctualLight>& lights, const RayScene* rays,
                      uint64_t& rays_cast, const Vec3* origin = nullptr);

struct DirectIrradiance {
  Vec3 mean;           // W/m², over the polygon
  double spread = 0;   // largest − smallest luminance over its points (how unevenly it is lit)
};

// Where the directional lights' rays first meet a surface facing them: for each light a grid × grid of
// parallel rays along it through a square about the scene's bounding sphere (cells outside its disc
// skipped), a spot where one meets a front face. They are points the light reaches that a receiver's
// stratified samples can all miss (the sun's patch through a window on a large floor: Refinement splits
// towards them). In row order, deterministic.
struct LightSpot {
  uint32_t polygon;
  Vec3 position;
};
inline constexpr int kSpotGrid = 1024;
std::vector<LightSpot> light_spots(const std::vector<PunctualLight>& lights, const Scene& scene, const RayScene& rays,
                                   int grid = kSpotGrid);

// Over n × n stratified points of the polygon (a convex triangle or quad).
DirectIrradiance direct_irradiance(const Polygon& p, const std::vector<PunctualLight>& lights, const RayScene* rays, int n,
                                   uint64_t& rays_cast);

}  // namespace walkrad
