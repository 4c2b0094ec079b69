// Shadow boundaries: the D1 discontinuities of an area emitter's direct light on a receiver's plane,
// where the part of the emitter a point sees changes form and the irradiance's slope jumps (for
// discontinuity meshing: discontinuity_mesh.h; Heckbert 1992, "Discontinuity meshing for radiosity"; Lischinski, Tampieri &
// Greenberg 1992). With polygonal emitters and occluders they lie on two kinds of critical surfaces:
//   EV: an emitter corner e passes behind an occluder's silhouette edge ab; on the plane, the edge's
//       shadow from e, its central projection p = e + (x − e)·h_e / (h_e − h_x) (h: height above the plane);
//   VE: an occluder's silhouette corner v passes in front of an emitter edge cd; on the plane, the
//       edge's image through v, p = v + (v − q)·h_v / (h_q − h_v).
// Left out: EEE surfaces (three edges in general position; curved, rare on the boxes of a room), and
// whether something else hides an event: a boundary drawn where nothing changes costs triangles, not
// accuracy. An occluder edge is a silhouette from a point where the occluders sharing it face that
// point the other way, or where none shares it (a panel, a shade).
#pragma once

#include <vector>

#include "walkrad/formats/scene.h"

namespace walkrad {

struct BoundarySegment {
  Vec3 a, b;
  // The point of the emitter whose visibility changes across the segment's middle: the corner (EV),
  // or the point of the emitter edge in line with the middle and the occluder's corner (VE).
  Vec3 flips;
};

// The EV and VE boundaries cast on `receiver`'s plane by `emitter` (its front towards the receiver)
// past `occluders`, clipped to the receiver (and to the box `within`, padded by tol, where given). tol:
// lengths below it are points (a segment shorter is dropped; an occluder lying in the receiver's plane
// casts nothing).
std::vector<BoundarySegment> shadow_boundaries(const Polygon& emitter, const Polygon& receiver,
                                               const std::vector<Polygon>& occluders, double tol,
                                               const Bounds* within = nullptr);

}  // namespace walkrad
