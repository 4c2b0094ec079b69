// The sky: an emitter at infinity whose radiance depends on the direction alone, seen through a level's
// windows, doors and open tops. Radiance in W/(m²·sr) per channel (read one for one, as emissive factors
// are). θ is the angle from the zenith (`up`), γ the angle from the sun:
//   uniform       L(ω) = L
//   cie-overcast  L(θ) = Lz (1 + 2 cos θ) / 3                    (Moon & Spencer 1942; the CIE's standard overcast sky)
//   cie-clear     L(θ, γ) = Lz f(γ) φ(θ) / (f(θs) φ(0))          (CIE 1973 clear sky, as Radiance's gensky +s)
//                 φ(θ) = 1 − exp(−0.32 / cos θ),  f(γ) = 0.91 + 10 exp(−3γ) + 0.45 cos² γ
//   image         an equirectangular radiance map (Radiance .hdr, stb_image), the whole sphere, laid out as
//                 three.js reads one with `up` as its +Y: column u = atan2(z, x) / 2π + ½, row from the top
//                 v = ½ − asin(y) / π (bilinear between pixels)
// The analytic skies are dark below the horizon: the ground is the scene's own geometry.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "walkrad/formats/vec3.h"

namespace walkrad {

struct PunctualLight;
struct Scene;

struct Sky {
  enum class Kind { uniform, cie_overcast, cie_clear, image };
  Kind kind = Kind::uniform;
  Vec3 radiance;         // uniform: L; the CIE skies: the zenith's Lz; image: a factor on the map (1)
  Vec3 up{0, 1, 0};      // unit, towards the zenith
  Vec3 sun{0, 1, 0};     // cie-clear: unit, towards the sun, above the horizon
  std::string path;      // image: where the .hdr was read from (the spec joined to the scene's folder)
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;  // image: row-major, top row (the zenith) first
  std::string spec;        // what it was made from: `walkrad convert` writes it back
  double mean_luminance = 0;  // over the directions with light: the scale of what the sky's rays tell apart

  // Radiance arriving from unit direction w (w points towards the sky).
  Vec3 at(const Vec3& w) const;
};

// Reads a sky from its spec:
//   uniform:L | uniform:R,G,B
//   cie-overcast:Lz | cie-overcast:R,G,B
//   cie-clear:Lz[@x,y,z]   the sun towards (x, y, z); without it, towards the scene's first directional light
//   FILE.hdr               an equirectangular radiance map, relative to `base` (empty: the working folder)
// `where` names the spec's origin in refusals ("--sky", or the glTF file and its place); `folder`, where
// not empty, is where an .hdr file must lie (a scene's input folder). `up` is the scene's zenith. Throws
// InputError: kExitBadArguments from "--sky", else kExitBadInput; a missing sun or a file too large as
// the other readers refuse them.
Sky parse_sky(const std::string& spec, const std::string& where, const std::string& place, const Vec3& up,
              const std::vector<PunctualLight>& lights, const std::string& base = {}, const std::string& folder = {});

// The command line's daylight, in this order: --up (the zenith "x,y,z", empty: the format's), --sun
// ("E@x,y,z": a directional light of irradiance E, one value or R,G,B in W/m², shining from towards x,y,z,
// of the sun's 0.53°; empty: none added; for scenes whose format has no sun, MGF), --sky (a spec, empty:
// the file's sky, if any; cie-clear may follow the sun just added). Throws InputError (kExitBadArguments)
// naming the option.
void apply_sky_options(Scene& scene, const std::string& sky, const std::string& up, const std::string& sun = {});

// "a CIE overcast sky (zenith 1000 W/(m²·sr), up +Z)", for the effect plan and messages.
std::string sky_description(const Sky& sky);

// Adds the sky to the scene's lights (a PunctualLight of type sky, named "sky"), replacing one already there.
void set_sky(Scene& scene, Sky sky);

}  // namespace walkrad
