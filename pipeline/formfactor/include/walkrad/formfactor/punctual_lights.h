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
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

// The distribution D towards unit direction `out` (from the light): 1 for a point light, the spot
// falloff, or the IES profile's candela (the light's intensity is per candela).
double light_distribution(const PunctualLight& light, const Vec3& out);

// The range window at distance r (1 without a range).
double range_window(const PunctualLight& light, double r);

// What the light radiates, W per channel: 4π I for a point, I ∫ spot dΩ for a spot, I × the
// profile's flux for a luminaire (the range's window ignored: it depends on what stands where).
Vec3 punctual_power(const PunctualLight& light);

// Irradiance at a surface point from every light; rays: occluders (nullptr: none). rays_cast counts.
// The shadow rays leave from origin when given (a point at a polygon's edge lies on its neighbour's
// plane: the caller moves it in), else from x lifted off its surface.
Vec3 point_irradiance(const Vec3& x, const Vec3& normal, const std::vector<PunctualLight>& lights, const RayScene* rays,
                      uint64_t& rays_cast, const Vec3* origin = nullptr);

struct DirectIrradiance {
  Vec3 mean;           // W/m², over the polygon
  double spread = 0;   // largest − smallest luminance over its points (how unevenly it is lit)
};

// Over n × n stratified points of the polygon (a convex triangle or quad).
DirectIrradiance direct_irradiance(const Polygon& p, const std::vector<PunctualLight>& lights, const RayScene* rays, int n,
                                   uint64_t& rays_cast);

}  // namespace walkrad
