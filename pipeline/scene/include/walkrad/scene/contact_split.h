// Contact splitting: where an edge of one polygon lies on another polygon (a wall standing on a
// floor, a box on a table), split that polygon along the edge's line, so that no element straddles
// the contact. An element that straddles a wall is lit on one side and re-emits that light on the
// other: the classic light leak under walls (algorithms.md §3, §8: a D0 discontinuity). Splitting
// by the full line keeps every piece convex; pieces with more than 4 corners become fans of quads
// and triangles.
// Near contacts too: a polygon parallel to another and in front of it within 2% of the smaller one's
// size (a lamp a few millimetres under a ceiling) covers it; the covered polygon is cut along the
// cover's outline, and the pieces under it take a copy of their material named "… (covered)", so
// that the output mesh does not average their dark corners with the lit ones beside them (the
// Cornell box's ceiling beside its light was 60–79% too dark at the outline).
#pragma once

#include <cstdint>

#include "walkrad/formats/scene.h"

namespace walkrad {

struct ContactSplitStats {
  uint64_t polygons_split = 0;  // input polygons cut at least once
  uint64_t cuts = 0;            // line cuts applied
  uint64_t covered = 0;         // pieces under a near-contact cover (given a covered copy of their material)
};

// Returns the scene with polygons split along contacts; materials and cameras are unchanged and
// every piece keeps its polygon's material and source. tolerance: distance (m) within which an
// edge counts as lying on a plane (default: 1e-6 of the scene's diagonal).
Scene split_contacts(const Scene& scene, ContactSplitStats& stats, double tolerance = 0);

}  // namespace walkrad
