// CIE colour for the MGF reader (mgf_reader.h): MGF's colour contexts (cxy chromaticities, cspec
// spectra, cct black bodies, cmix mixtures) and their conversion to linear sRGB.
//
// Colour model (the MGF specification, "c" and "cxy"; G. Ward, LBNL 1995): a colour is a
// chromaticity only; the luminance comes from the material value that takes it (rd, ed, ...).
// Spectra and black bodies are reduced to CIE XYZ with the CIE 1931 2° standard observer.
// Conversion to walkrad's linear RGB:
//   1. XYZ of chromaticity (x, y) at luminance Y: (x/y·Y, Y, (1-x-y)/y·Y).
//   2. MGF's neutral is the equal-energy white E (x = y = 1/3); sRGB's is D65. E is mapped onto D65
//      by scaling X and Z (a von Kries step in XYZ), which keeps Y: a neutral stays neutral and
//      the luminance of the result (Rec. 709 coefficients, vec3.h luminance()) is Y.
//   3. Linear sRGB from XYZ with the matrix of the Rec. 709 primaries and D65 white (IEC 61966-2-1).
//   4. A colour outside the sRGB gamut (a negative channel) is desaturated towards the grey of the
//      same luminance until its smallest channel is 0: luminance and hue angle are kept.
// Chromaticities within 0.001 of (1/3, 1/3) in x and y count as neutral: files write 0.333 0.333
// for MGF's neutral, and 0.001 is below a just-noticeable chromaticity difference.
#pragma once

#include <utility>
#include <vector>

#include "walkrad/formats/vec3.h"

namespace walkrad::mgf {

// Luminous efficacy of equal-energy white light over the visible range with the CIE 1931 observer,
// lm/W (Radiance's WHITE_EFFICACY; RenderPark uses 183.07 with the CIE 1988 observer):
// an MGF emittance ed (lm/m²) is ed / 179 W/m² of emitted radiosity.
constexpr double kWhiteEfficacy = 179.0;

// A colour as MGF's parser keeps it: CIE XYZ per unit of mixing weight. A chromaticity weighs by
// luminance (Y = 1 per unit weight); a spectrum weighs by power (samples normalised to mean 1), as
// MGF's own cmix does. Only the direction of xyz matters for the colour itself.
struct Colour {
  Vec3 xyz{1, 1, 1};  // the default colour: equal-energy white, MGF's neutral
};

// Precondition: x >= 0, y >= 0, x + y <= 1. y = 0 (allowed by MGF) has no luminance: the colour
// is black whatever value takes it, as in RenderPark.
Colour colour_from_xy(double x, double y);
inline bool is_black(const Colour& c) { return !(c.xyz.y > 0); }

// A spectrum of samples evenly spaced over [lmin, lmax] nm (both included, lmin < lmax, at least
// two samples, none negative). False when it has no luminance in 380-780 nm.
bool colour_from_spectrum(double lmin, double lmax, const std::vector<double>& samples, Colour& out);

// A black body (Planck's law) at the given temperature in kelvin. False outside 1000-100000 K.
bool colour_from_temperature(double kelvin, Colour& out);

// The mixture of (weight, colour) pairs; weights >= 0 with a positive sum.
Colour colour_mix(const std::vector<std::pair<double, Colour>>& parts);

// CIE (x, y) chromaticity.
std::pair<double, double> chromaticity(const Colour& c);
bool is_neutral(const Colour& c);

// Linear sRGB of the colour at luminance Y (steps 1-4 above); black for a black colour.
// desaturated (optional) tells whether step 4 changed it.
Vec3 linear_srgb(const Colour& c, double luminance, bool* desaturated = nullptr);

}  // namespace walkrad::mgf
