// Contact splitting: where an edge of one polygon lies on another polygon (a wall standing on a
// floor, a box on a table), split that polygon along the edge's line, so that no element straddles
// the contact. An element that straddles a wall is lit on one side and re-emits that light on the
// other: the classic light leak under walls (algorithms.md §3, §8: a D0 discontinuity). Splitting
// by the full line keeps every piece convex; pieces with more than 4 corners become fans of quads
// and triangles.
// Near contacts too: a polygon parallel to another and in front of it within 2% of the smaller one's
// size (a lamp a few millimetres under a ceiling) covers it; the covered polygon is cut along the
// cover's outline, and the pieces under it take a copy of their material named "… (covered)", so
// that the output mesh does not average their dark corners with the lit ones beside them (averaged,
// the Cornell box's ceiling beside its light is 60–79% too dark at the outline). So do pieces enclosed by
// what stands on them: something stands along an edge with its back to the piece, nothing along any
// edge faces it (a shelf board under a book with no bottom face).
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/scene/cluster_tree.h"

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

// Near-contact bands: a cover darkens the polygon under it beside its footprint as well. A point at
// distance d outside a long edge of a cover at gap g sees the cover's underside (dark: it faces the
// covered strip) at the form factor ½(1 − d/√(g² + d²)): 0.34 at d = g/3, 0.015 at d = 4 g. For each
// polygon of a scene already split (split_contacts) that `wanted` selects, the outlines of its covers'
// footprints grown by kContactBand gaps, as segments on its plane clipped to it: the output mesh cuts
// its faces along them (discontinuity_mesh.h), so that the darkening stays in a band of that width
// and Gouraud shading does not carry an outline vertex's darkness across a wider triangle (test
// ContactShadow: a point 1 cm beside a box 2 mm above the floor took a quarter of a vertex 0.7 mm
// from the outline, 35% dark).
constexpr double kContactBand = 4.0;
struct ContactBand {
  Vec3 a, b;
};
// tree: build_cluster_tree(scene), as the bake already holds it (Hierarchy::tree).
std::vector<std::vector<ContactBand>> contact_bands(const Scene& scene, const ClusterTree& tree, const std::vector<uint8_t>& wanted,
                                                    double tolerance = 0);

}  // namespace walkrad
