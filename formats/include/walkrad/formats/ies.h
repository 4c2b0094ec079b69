// IES photometric data (ANSI/IES LM-63: the 1986/1991 files without a first line, IESNA:LM-63-1995,
// IESNA:LM-63-2002 and IES:LM-63-2019): a luminaire's luminous intensity, candela, tabulated on a web
// of vertical × horizontal angles, the way manufacturers publish luminaires. Read by parse_ies into
// plain data; intensity() interpolates it as the standard says (bilinear in the two angles, the
// symmetric quadrants mirrored, nothing outside the measured range).
//
// The light's frame is the one glTF EXT_lights_ies and MGF's `ies` entity use: the zero point of the
// web (both angles 0, where type C's nadir and types A/B's aim lie) is −Z; X/Z is the vertical
// photometric plane of horizontal angle 0, towards +X.
//   Type C: vertical angle γ from −Z, horizontal angle C counter-clockwise seen from +Z, 0 at +X,
//           90 at +Y: d = (sin γ cos C, sin γ sin C, −cos γ).
//   Type B: the planes turn about the lateral axis; V is the plane's elevation towards +X, H the
//           lateral angle inside it, positive towards −Y (the standard's clockwise):
//           d = cos H · (cos V · (−Z) + sin V · X) + sin H · (−Y).
//   Type A: the planes turn about the vertical (+X) axis; H the plane's angle towards −Y, V the
//           elevation inside it: d = cos V · (cos H · (−Z) + sin H · (−Y)) + sin V · X.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "walkrad/formats/vec3.h"

namespace walkrad {

// Limits checked before anything is allocated from what a file declares (README.md, "Limits"; past
// them: kExitLimitReached). Published luminaires use a few hundred angles and values; 1° steps over
// the whole sphere are 181 × 361.
inline constexpr int kMaxIesAngles = 10'000;       // vertical, horizontal and tilt angles, each
inline constexpr long kMaxIesCandela = 4'000'000;  // vertical × horizontal candela values
inline constexpr uint64_t kMaxIesBytes = uint64_t(16) << 20;  // a file (published ones are a few KiB)

struct IesProfile {
  enum class Photometry : uint8_t { C = 1, B = 2, A = 3 };

  std::string source;   // the file it was read from (or a label), for messages
  std::string version;  // "LM-63-1986" (no version line), "LM-63-1991" (IESNA91), "LM-63-1995",
                        // "LM-63-2002" or "LM-63-2019"
  Photometry photometry = Photometry::C;
  std::vector<double> vertical;    // degrees, strictly ascending, as in the file
  std::vector<double> horizontal;  // degrees, strictly ascending, as in the file
  // candela[h · vertical.size() + v], already multiplied by the file's candela multiplier, ballast
  // factor and ballast-lamp photometric factor (up to LM-63-1995; the same field is "future use" in
  // 2002 and 2019, 1 there, and not applied).
  std::vector<double> candela;
  // TILT=INCLUDE: the lamp-to-luminaire geometry and the multiplying factor at each tilt angle
  // (degrees). Empty for TILT=NONE.
  int lamp_geometry = 0;
  std::vector<double> tilt_angles, tilt_factors;
  int lamps = 1;
  double lumens_per_lamp = -1;  // −1: absolute photometry
  double input_watts = 0;
  std::string text;  // the file's bytes as parsed (the glTF writer writes them back)

  // Candela towards photometric angles (degrees) in the file's own convention, by symmetry and
  // bilinear interpolation; 0 outside the measured range.
  double candela_at(double vertical_deg, double horizontal_deg) const;
  // Candela towards a unit direction in the light's frame (above).
  double intensity(const Vec3& direction) const;
  // The tilt multiplying factor for a luminaire tilted by `tilt_deg` from its measured position,
  // interpolated in the table (clamped at its ends); 1 without tilt data.
  double tilt_factor(double tilt_deg) const;
  // The same for a luminaire aimed along `aim`, its photometric position aiming along `down` (the
  // scene's gravity: glTF −Y, MGF −Z): its tilt is the angle between them.
  double tilt_factor(const Vec3& aim, const Vec3& down) const;
  // Luminous flux, lm: ∫ intensity dΩ over the sphere (numerical, exact for the interpolation to
  // within 1e-4 relative).
  double flux() const;
  double max_candela() const;
};

// Parses the text of an IES file. Throws InputError (kExitBadInput) naming `source` and "line N"
// for anything malformed, truncated or out of range (counts, angles not ascending or outside the
// photometric type's range, negative candela, non-finite numbers); TILT=<file> is refused with
// kExitMissingFeature. Counts are bounded before anything is allocated.
IesProfile parse_ies(std::string_view text, const std::string& source);

// Reads and parses a file (a regular file, at most 16 MiB; larger: kExitLimitReached).
IesProfile read_ies(const std::string& path);

}  // namespace walkrad
