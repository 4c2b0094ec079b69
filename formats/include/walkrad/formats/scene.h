// The plain scene arrays that every reader (glTF, MGF) produces and every later stage consumes:
// planar polygons (triangles and quads) in world space, metres, with diffuse materials, plus the
// viewpoints (cameras) found in the scene file. No pointers into reader-specific structures.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "walkrad/formats/ies.h"
#include "walkrad/formats/sky.h"
#include "walkrad/formats/vec3.h"

namespace walkrad {

// A diffuse material. Radiosity B = π·L (W/m²), so emission is stored as emitted radiosity
// E = π × emitted radiance (../shared/design/algorithms.md §1).
struct Material {
  std::string name;
  Vec3 reflectance;  // diffuse ρ per channel, in [0, 1)
  Vec3 emission;     // emitted radiosity E, W/m², per channel
  Vec3 transmittance = {};  // diffuse τ per channel: the share of light arriving on one side that leaves the
                       // other (lampshades, curtains); ρ + τ ≤ 1
  // Textures (Scene::textures, −1: none) that modulate reflectance and emission over a surface. The
  // values above are already the texture's average times the factor; where a polygon has texture
  // coordinates, elements take the texture's mean over their own area instead (texture.h).
  int32_t reflectance_texture = -1, emission_texture = -1;
  // Clear glass: a thin pane whose transmission has no roughness passes light straight through, times
  // this filter (per channel) and the Fresnel transmittance of a pane of index `ior` for the angle
  // (clear_glass.h). The bake takes such polygons out of the solve (Scene::glass): rays cross them.
  Vec3 clear = {};
  double ior = 1.5;
  bool emits() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }
  bool transmits() const { return transmittance.x > 0 || transmittance.y > 0 || transmittance.z > 0; }
  bool is_clear_glass() const { return clear.x > 0 || clear.y > 0 || clear.z > 0; }
};

// A planar, convex polygon with 3 or 4 vertices, counter-clockwise seen from its front (the side
// its normal points to). Only the front side exchanges light.
// Texture coordinates on a planar polygon are an affine function of position: u = a_u · p + b_u,
// v = a_v · p + b_v. Kept as that function, they survive any cut of the polygon unchanged.
struct UvMap {
  bool valid = false;
  Vec3 a_u, a_v;
  double b_u = 0, b_v = 0;
  double u(const Vec3& p) const { return dot(a_u, p) + b_u; }
  double v(const Vec3& p) const { return dot(a_v, p) + b_v; }
};

struct Polygon {
  std::array<Vec3, 4> v{};
  uint8_t count = 3;
  uint32_t material = 0;
  uint32_t source = 0;  // the input primitive it came from (glTF mesh index, MGF face line), for messages
  UvMap uv = {};        // texture coordinates, where the material has a texture
};

// A texture in linear RGB (sRGB-decoded), sampled bilinearly with repeat (glTF's defaults).
struct Texture {
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;  // row-major, top row first (as images are stored; v = 0 at the top)
  Vec3 mean;               // over all texels
  Vec3 at(double u, double v) const;
};

// Readers refuse vertices beyond ±kMaxCoordinate metres (a million km): past it, areas and form
// factors lose all precision long before they overflow to infinity.
constexpr double kMaxCoordinate = 1e9;
inline bool is_valid_vertex(const Vec3& v) {
  return is_finite(v) && std::fabs(v.x) <= kMaxCoordinate && std::fabs(v.y) <= kMaxCoordinate && std::fabs(v.z) <= kMaxCoordinate;
}

// Unnormalised normal: its length is twice the area (Newell's method, robust for quads).
Vec3 polygon_area_normal(const Polygon& p);
Vec3 polygon_normal(const Polygon& p);
double polygon_area(const Polygon& p);
Vec3 polygon_centroid(const Polygon& p);  // area centroid

// A pinhole viewpoint. forward and up are unit and orthogonal; yfov in radians.
struct Viewpoint {
  std::string name;
  Vec3 position;
  Vec3 forward{0, 0, -1};
  Vec3 up{0, 1, 0};
  double yfov = 0.8;
  double aspect = 1.0;  // width / height
};

// A punctual light (glTF KHR_lights_punctual): a point, or a spot shining along `direction` with the
// extension's smooth falloff between the inner and outer cone. Its intensity is read as radiant
// intensity, W/sr per channel (colour × intensity, the candela read one for one as W/sr, as emissive
// factors are read as radiance). range > 0: the extension's window, nothing beyond it.
// A luminaire (glTF EXT_lights_ies, MGF `ies`) is a point whose intensity varies with direction as
// its IES profile says: W/sr = `intensity` (colour × multiplier × tilt factor) × the profile's candela
// towards the direction, in the light's frame (ies.h; light_frame below): the web's zero point along
// `direction` (the node's −Z), type C's horizontal angle 90° along `up` (the node's +Y).
// A directional light (the sun) shines along `direction` from infinitely far: its intensity is read as
// irradiance, W/m² per channel on a surface facing it (the lux read one for one as W/m²), its light
// arriving from a disc of `angular_diameter` around −direction (the sun's 0.53°: its shadows' penumbra);
// position and range mean nothing for it.
// The sky (sky.h) is a light too: an emitter at infinity, its radiance `sky->at(ω)` times `intensity`
// (1, 1, 1) from every direction it reaches a point through the scene's openings.
inline constexpr double kSunDiameter = 0.53 * kPi / 180;  // the sun's, seen from the Earth
inline constexpr double kMaxAngularDiameter = 0.5;  // radians: a wider source is a sky, not a sun

struct PunctualLight {
  enum class Type { point, spot, ies, directional, sky };
  std::string name;
  Type type = Type::point;
  Vec3 position;
  Vec3 direction{0, 0, -1};  // spot, ies: unit; the node's −Z
  Vec3 up{0, 1, 0};          // ies: unit, orthogonal to direction; the node's +Y
  Vec3 intensity;            // W/sr per channel (ies: per candela)
  double range = 0;          // metres; 0: unlimited
  double inner_cone = 0, outer_cone = 0.7853981633974483;  // spot: radians, 0 ≤ inner < outer ≤ π/2
  double angular_diameter = kSunDiameter;                  // directional: radians, 0 (a hard shadow) to kMaxAngularDiameter
  std::shared_ptr<const IesProfile> profile;  // ies: the photometric data (shared, never changed)
  std::shared_ptr<const Sky> sky;             // sky: its radiance over the directions (shared, never changed)
};

// `up` made orthogonal to the unit `direction` and unit (a light node's +Y under any transform); the
// zero vector where it is (nearly) parallel to it.
inline Vec3 orthogonal_up(const Vec3& direction, const Vec3& up) {
  const Vec3 u = up - direction * dot(up, direction);
  return length(u) > 1e-9 * length(up) ? normalize(u) : Vec3{};
}

// A world direction in a luminaire's own frame (ies.h): its node's X, Y and Z axes.
inline Vec3 light_frame(const PunctualLight& l, const Vec3& world) {
  const Vec3 z = -l.direction, y = l.up, x = cross(y, z);
  return {dot(world, x), dot(world, y), dot(world, z)};
}

struct Scene {
  std::string source;  // the file it was read from
  std::vector<Material> materials;
  std::vector<Polygon> polygons;
  std::vector<Viewpoint> cameras;  // viewpoints found in the scene file itself (glTF camera nodes)
  std::vector<PunctualLight> lights;  // glTF KHR_lights_punctual, EXT_lights_ies, MGF ies, the sky (sky.h)
  std::vector<Polygon> glass;         // clear-glass panes taken out of `polygons` (separate_clear_glass): rays cross them
  Vec3 up{0, 1, 0};                   // the zenith, for a sky: glTF's +Y, MGF's +Z
  std::vector<Texture> textures;      // reflectance and emission textures (Material::*_texture)
  uint64_t dropped_degenerate = 0;     // zero-area triangles dropped by the reader
  std::vector<std::string> warnings;  // what the reader changed or ignored, for the user

  Bounds bounds() const;
};

}  // namespace walkrad
