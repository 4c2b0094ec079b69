// Reads an MGF scene (Materials and Geometry Format 1.1, G. Ward, LBNL; the format of RenderPark's
// classic radiosity scenes) into the plain scene arrays (scene.h) that every later stage shares.
//
// What is read:
// - vertices (v, p, n), faces (f with any number of vertices, concave or with seams; fh with holes),
//   split into planar convex triangles and quads (mgf_geometry.h);
// - the curved primitives sph, cyl, cone, ring, torus and prism, tessellated so that no chord
//   leaves the true surface by more than MgfOptions::tolerance × its radius;
// - transforms (xf with -t -rx -ry -rz -s -mx -my -mz -i -a) on a stack, arrays repeated; includes
//   (i, with a transform; paths relative to the including file, inside MgfOptions::input_folder;
//   cycles and depths over 32 refused);
//   objects (o); luminaires (ies pathname [-m multiplier] [transform]: an IES LM-63 profile, ies.h, as a
//   punctual light at the transform's origin, one per array instance; candela ÷ 179 lm/W → W/sr in
//   the current colour, as ed; TILT factors at the luminaire's tilt from straight down, −Z);
// - materials (m, rd, ed, sides; td, rs, ts, ir are checked and ignored: walkrad is diffuse) and
//   colours (c, cxy, cspec, cct, cmix).
// Conventions:
// - Units: MGF coordinates are metres (the MGF spec); they are taken as they are.
// - Colour: linear sRGB (Rec. 709 primaries, D65), MGF's neutral (equal-energy white) mapped to
//   D65 keeping luminance, so luminance(reflectance) = rd (mgf_colour.h). "cxy .333 .333" is grey.
// - Reflectance ρ = rd in the current colour, capped at 0.99 per channel (with a warning); rd 1 is
//   kept (at most 1 per channel), with a warning: the bake refuses a closed scene where nothing absorbs.
// - Emission: ed is an emittance in lm/m²; E = ed / 179 W/m² of emitted radiosity (179 lm/W is
//   the efficacy of equal-energy white, Radiance's WHITE_EFFICACY), in the colour of ed.
// - Sides: a material with "sides 2" gives each face a second polygon with reversed winding, so
//   both sides exchange light (and an emitter emits from both). A material that does not state
//   sides is one-sided unless MgfOptions::default_sides says 2: MGF's default is two-sided, but
//   the classic radiosity scenes were made for RenderPark, which forces one-sided surfaces.
// - Polygon::source is the line of the entity (in the file that holds it).
// Unknown entities are skipped and counted (one warning per keyword); malformed entities throw
// InputError naming the file and "line N".
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "walkrad/formats/scene.h"

namespace walkrad {

struct MgfOptions {
  // Chord deviation from the true curve, as a fraction of the radius, in [1e-4, 0.5]. The default
  // gives 4 segments per quarter circle, RenderPark's tessellation.
  double tolerance = 0.02;
  int default_sides = 1;                // 1 or 2: the sides of a material that does not say
  uint64_t max_polygons = 50'000'000;   // more is refused (kExitLimitReached)
  // Where included files and IES profiles may lie; empty: the scene file's own folder. A path outside
  // it is refused (InputError, kExitBadInput) before it is opened.
  std::string input_folder;
};

// What the reader met, for tests and reports. Array instances and repeated includes count each time.
struct MgfStats {
  std::map<std::string, uint64_t> entities;  // known entities by keyword (comments not counted)
  uint64_t faces = 0;                // f and fh
  uint64_t emitting_faces = 0;       // f and fh with an emitting material
  uint64_t primitives = 0;           // sph, cyl, cone, ring, torus, prism
  uint64_t emitting_primitives = 0;
  uint64_t files = 0;                // files read, the scene file included
  uint64_t back_polygons = 0;        // polygons added for the back of two-sided materials
};

// Throws InputError (malformed or missing input, kExitLimitReached past a limit) and
// std::invalid_argument for options out of range.
Scene read_mgf(const std::string& path, const MgfOptions& options = {}, MgfStats* stats = nullptr);

}  // namespace walkrad
