// Discontinuity meshing of the output (Lischinski, Tampieri & Greenberg 1992): the faces a
// walkthrough sees are cut along the shadow boundaries of the emitters that light them
// (shadow_boundaries.h), so that output vertices lie where the direct light's slope jumps and
// Gouraud shading bends there, instead of wherever the solution's quadtree edges happen to fall. The
// final gather then evaluates the direct light exactly at those vertices (final_gather.h). The
// solution is untouched: a cut face's pieces keep its leaf, its radiosity and its links.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/hierarchical/final_gather.h"
#include "walkrad/output/shadow_boundaries.h"
#include "walkrad/output/surface_mesher.h"

namespace walkrad {

// The boundaries to cut, by input polygon: for each seen face's polygon (seen(face)), each emitter its
// faces gather (emitters[face]) past the polygons in the shaft between the two (shaft.h), ranked by
// their contrast (the receiver's reflectance times the emitter's unoccluded irradiance at the
// segment's middle, in luminance) and kept, the strongest first, while the faces they are expected
// to cross stay within `budget`. Deterministic: in parallel over polygons, ranked with ties broken
// by polygon and order of discovery.
struct BoundarySelection {
  std::vector<std::vector<BoundarySegment>> by_polygon;
  std::vector<std::vector<uint32_t>> emitter;  // by polygon, of each segment: its emitter (DirectGather's index)
  uint64_t segments = 0;  // kept
  uint64_t found = 0;     // active, before the budget
  uint64_t hidden = 0;    // found where nothing changes (the emitter point seen from both sides or neither)
};
// rays (null: none tested): a boundary is kept only where the emitter point it is drawn for
// (BoundarySegment::flips) is seen from one side of its middle and hidden from the other: an event that
// something else hides (a box's shadow boundary inside another's umbra) changes nothing there.
BoundarySelection select_boundaries(const Hierarchy& h, const DirectGather& direct, const MeshFaces& faces,
                                    const std::vector<uint8_t>& seen, const std::vector<EmitterRanges>& emitters,
                                    uint64_t budget, const RayScene* rays);

// Cuts each face along the segments of its polygon that cross it, each by its whole line within the
// face (the pieces stay convex; a piece of more than 4 corners is fanned), skipping a cut that would
// leave a piece of less than min_share of the face's area or thinner than 4 snap. A corner within snap
// of a line counts as on it: no new corner lands within snap of another. snap: above what the output's
// position quantum (Draco's grid) can move a vertex and an edge towards each other, so that no corner
// or fan centre lands on an edge it does not belong to (a T-junction in the chunks, none in the
// mesher's doubles). Returns the pieces in face order and, for
// each, the face it came from; and for each face the segments (indices in its polygon's list) that
// cut it. The mesher then anchors the T-vertices the cuts leave on the
// neighbours' edges (surface_mesher.h): the mesh stays crack-free.
struct CutFaces {
  MeshFaces faces;
  std::vector<uint32_t> from;
  std::vector<std::vector<uint32_t>> applied;  // by input face
};
CutFaces cut_faces(const MeshFaces& faces, const std::vector<std::vector<BoundarySegment>>& by_polygon,
                   double snap, double min_share = 1e-3);

}  // namespace walkrad
