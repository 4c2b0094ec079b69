// Proven occlusion: whether no segment between two convex sets can pass, where a finite number of
// rays only says that none of theirs did (the conservative "blocked" class of Teller & Hanrahan,
// "Global visibility algorithms for illumination computations", SIGGRAPH 1993).
//
// A plane P with one set on each closed side meets every segment between them inside
//   R = conv(A ∪ B) ∩ P = conv{ a_i + t (b_j − a_i) ∈ P },
// the hull of where the segments between their corners cross it. If polygons lying in P cover R,
// every segment meets one of them. A wall modelled as several coplanar quads (around a doorway, one
// per room, back to back with the next room's) covers R together; a doorway in R leaves part of it
// uncovered, and nothing is proven. The planes tried are those of the polygons the caller names
// (the first surfaces its blocked rays met). Polygons in the plane past a few dozen, or a cover cut into
// more pieces than a few dozen, prove nothing: a wall is a few quads; clutter is left to refinement.
//
// A set's polygons lying in P itself must face away from the other set (they are then part of the
// wall, seen from their own side); one that faces the other set would send light past the cover.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/scene/cluster_tree.h"

namespace walkrad {

class OcclusionProof {
 public:
  OcclusionProof(const Scene& scene, const ClusterTree& tree);

  // One end: the corners of its convex hull (an element's vertices, or a cluster's box), and for a
  // cluster its ClusterTree node (whose polygons lying in P are checked as above; UINT32_MAX for an
  // element, which lies in P only if it is coplanar with it, and then nothing is separated).
  struct End {
    const Vec3* corners = nullptr;
    int count = 0;
    uint32_t tree_node = UINT32_MAX;
  };
  static End element(const Polygon& shape) { return {shape.v.data(), shape.count, UINT32_MAX}; }
  // A box's 8 corners, written to `corners`.
  static End box(const Bounds& b, uint32_t tree_node, Vec3 (&corners)[8]);

  // True where the plane of one of `planes` (polygon indices, duplicates allowed) proves that nothing
  // passes between a and b. Thread-safe.
  bool blocked(const End& a, const End& b, const uint32_t* planes, size_t count) const;

 private:
  // The same, for one plane given by a point, a unit normal and the polygon of it the ray met first.
  bool blocked_by_plane(const End& a, const End& b, const Vec3& point, const Vec3& normal, uint32_t first) const;

  const Scene& scene_;
  const ClusterTree& tree_;
  double size_ = 1;  // the scene's diagonal
};

}  // namespace walkrad
