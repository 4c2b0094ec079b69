// The adaptive output mesh. The display interpolates (Gouraud) between vertices that take the solution
// at their own position, so a leaf shows what its corners say: a lamp centred over a table lights the
// table's middle most, and the table kept as one leaf shows its corners' light everywhere (a 1 m square
// 1 m under a 1 m square emitter: its corners' light is 31% below its mean and 42% below its centre's,
// by the contour formula). A leaf whose shown direct light, evaluated at its edges' quarter, half and three-quarter
// points and its centre, departs from what Gouraud shading interpolates between its corners by more
// than kInterpolationShare of its tolerance (e × what it shows) is split in four, the worst first, and
// its children are tested again, while the new leaves stay within `budget`.
//
// What "shown" means depends on the leaf: a gathered leaf (final_gather.h) shows ρ D(x) from the
// emitters its gather reaches, with shadow rays; another leaf shows its close luminaires' light at the
// point, ρ Σ E_s F(x → s) · F/F_open over the emitting sources LeafRadiosity takes at the point
// (point_radiosity.h: taken_at_points). The children take their parent's solution (B, factors): they
// have no links of their own, and the vertices below read their ancestors'. In a fixed order:
// deterministic. Returns the splits.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/hierarchical/error_presets.h"
#include "walkrad/hierarchical/final_gather.h"
#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad {

// The interpolation error allowed, as a share of the solution's tolerance: an eighth. The 1 m square
// under the 1 m emitter at the default error: a quarter stops at 4 × 4 leaves, whose Gouraud mean is
// 1.9% below the true mean; an eighth at 8 × 8, 0.5% below.
constexpr double kInterpolationShare = 0.125;

struct DisplayRefinement {
  const std::vector<uint8_t>* seen = nullptr;   // per input polygon, 1: gathered (null: all, when gathering)
  const std::vector<uint32_t>* twins = nullptr; // transmitting polygons (kNoTwin: none): split for both sides' lights
  // The leaves that are not gathered are tested too: a bake without viewpoints (or view-independent),
  // where every surface is what the display shows.
  bool ungathered = false;
  double error = kDefaultError;                 // relative to what the leaf shows
  double white = 0;                             // the display's white (luminance, W/m²)
  double min_area = 0;                          // no leaf below it
  int max_depth = 16;
  uint64_t budget = 0;                          // new leaves at most
};

// gather: the final gather's direct light (null: no leaf is gathered).
uint64_t refine_display(Hierarchy& h, const DirectGather* gather, const DisplayRefinement& r, uint64_t& rays_cast);

}  // namespace walkrad
