// Shaft culling (Haines & Wallace, "Shaft culling for efficient ray-traced radiosity", EGWR 1991).
// The shaft between two axis-aligned boxes is their convex hull: the box around both, cut by up to
// 8 planes through pairs of parallel box edges. A polygon outside the shaft cannot block any segment
// between the two boxes; a shaft that holds no candidate means visibility 1 with no ray cast, for
// the two nodes and for all their children (whose shafts lie inside it), so a link's candidate list
// is filtered, not recomputed, for its children.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/pipeline/cluster_tree.h"

namespace walkrad {

class Shaft {
 public:
  Shaft(const Bounds& a, const Bounds& b);

  // Conservative: false only if the box lies entirely outside the shaft.
  bool overlaps(const Bounds& box) const;
  int plane_count() const { return planes_; }

 private:
  Bounds hull_;
  struct Plane {
    Vec3 n;     // outward
    double d;   // points x with dot(n, x) > d are outside
  };
  Plane plane_[12];
  int planes_ = 0;
};

// Polygons of the tree (other than exclude_a and exclude_b, the two ends' own polygons) whose
// bounds overlap the shaft, in tree order.
std::vector<uint32_t> shaft_candidates(const ClusterTree& tree, const Shaft& shaft, uint32_t exclude_a, uint32_t exclude_b);

// The subset of candidates (a parent link's list) that overlaps a child link's shaft.
std::vector<uint32_t> filter_candidates(const ClusterTree& tree, const Shaft& shaft, const std::vector<uint32_t>& candidates,
                                        uint32_t exclude_a, uint32_t exclude_b);

}  // namespace walkrad
