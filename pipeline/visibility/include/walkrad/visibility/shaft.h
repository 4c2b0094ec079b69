// Shaft culling (Haines & Wallace, "Shaft culling for efficient ray-traced radiosity", EGWR 1991).
// The shaft between two axis-aligned boxes is their convex hull: the box around both, cut by up to
// 8 planes through pairs of parallel box edges. A polygon outside the shaft cannot block any segment
// between the two boxes; a shaft that holds no candidate means visibility 1 with no ray cast, for
// the two nodes and for all their children (whose shafts lie inside it), so a link's candidate list
// is filtered, not recomputed, for its children.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "walkrad/scene/cluster_tree.h"

namespace walkrad {

class Shaft {
 public:
  Shaft(const Bounds& a, const Bounds& b);

  // Conservative: false only if the box lies entirely outside the shaft.
  bool overlaps(const Bounds& box) const;
  // True only if the box lies strictly inside the shaft less its margin, so that overlaps() holds
  // for every box inside it.
  bool contains(const Bounds& box) const;
  int plane_count() const { return planes_; }

 private:
  Bounds hull_;
  // Each plane is parallel to the third axis: its normal has two components, on axes k < l (the
  // third is exactly 0, so two terms give dot(n, x) to the bit).
  struct Plane {
    double nk, nl;  // outward
    double d;       // points x with nk x_k + nl x_l > d are outside
    double Vec3::*k;
    double Vec3::*l;
    // A box's corner furthest inside (most negative along n) and furthest out, on each axis.
    Vec3 Bounds::*inner_k;
    Vec3 Bounds::*inner_l;
    Vec3 Bounds::*outer_k;
    Vec3 Bounds::*outer_l;
  };
  Plane plane_[12];
  int planes_ = 0;
  // What overlaps() compares against, computed once (it runs for every tree node a link's shaft
  // meets: half of a large level's solve): the hull shrunk by the margin, whether each axis is flat,
  // and each plane's d less the margin.
  Vec3 inner_lo_, inner_hi_;
  bool flat_[3] = {};
  double inner_d_[12] = {};
};

// Polygons of the tree (other than exclude_a and exclude_b, the two ends' own polygons) whose
// bounds overlap the shaft, in tree order.
std::vector<uint32_t> shaft_candidates(const ClusterTree& tree, const Shaft& shaft, uint32_t exclude_a, uint32_t exclude_b);

// The subset of candidates (a parent link's list) that overlaps a child link's shaft.
std::vector<uint32_t> filter_candidates(const ClusterTree& tree, const Shaft& shaft, const std::vector<uint32_t>& candidates,
                                        uint32_t exclude_a, uint32_t exclude_b);

// Compact candidate lists (no volumes), for the hierarchical solver, whose links' shafts nest: a tree
// node wholly inside the shaft is one entry (its index with kWholeNode) standing for every polygon
// below it, so a child link filters a cluster of thousands of polygons with one test where it is
// still wholly inside, and opens it only where the shaft's side crosses it. Polygon entries are
// exclude_a and exclude_b dropped; node entries keep them, and candidate_count() takes them off.
// Expanded (expand_candidates), a compact list is exactly shaft_candidates()'s list, in the same order.
constexpr uint32_t kWholeNode = 0x20000000u;
std::vector<uint32_t> compact_candidates(const ClusterTree& tree, const Shaft& shaft, uint32_t exclude_a, uint32_t exclude_b);
std::vector<uint32_t> filter_compact_candidates(const ClusterTree& tree, const Shaft& shaft, const std::vector<uint32_t>& candidates,
                                                uint32_t exclude_a, uint32_t exclude_b);
size_t candidate_count(const ClusterTree& tree, const std::vector<uint32_t>& candidates, uint32_t exclude_a, uint32_t exclude_b);
// min(limit, candidate_count(filter_compact_candidates(...))) without building the list: a link that
// is not split further needs only whether it has 0, more than 4 or more than 64 candidates.
size_t count_compact_candidates(const ClusterTree& tree, const Shaft& shaft, const std::vector<uint32_t>& candidates,
                                uint32_t exclude_a, uint32_t exclude_b, size_t limit);
std::vector<uint32_t> expand_candidates(const ClusterTree& tree, const std::vector<uint32_t>& candidates, uint32_t exclude_a,
                                        uint32_t exclude_b);

// Volumetric visibility (volume_visibility.h): what lies in volume clusters and the multi-resolution
// rule lets stand in as a medium is kept whole as one candidate, tagged: a ClusterTree node wholly in
// volumes (its index with kVolumeNode), or a polygon in a volume (its index with kVolumePolygon).
constexpr uint32_t kVolumeNode = 0x80000000u;
constexpr uint32_t kVolumePolygon = 0x40000000u;
constexpr uint32_t kVolumeTags = kVolumeNode | kVolumePolygon;

struct VolumeTags {
  const std::vector<uint8_t>& node;     // per tree node: every polygon below is in a volume
  const std::vector<uint8_t>& polygon;  // per polygon: in a volume
  std::function<bool(uint32_t tagged)> see_through;  // the rule, for a tagged candidate
};

// As above, with volume candidates kept whole where tags.see_through accepts them.
std::vector<uint32_t> shaft_candidates(const ClusterTree& tree, const Shaft& shaft, uint32_t exclude_a, uint32_t exclude_b,
                                       const VolumeTags& tags);
// A parent's list (possibly tagged) for a child link: a tagged candidate the rule no longer accepts is
// opened (a node into its polygons and the finer volume candidates the rule accepts).
std::vector<uint32_t> filter_candidates(const ClusterTree& tree, const Shaft& shaft, const std::vector<uint32_t>& candidates,
                                        uint32_t exclude_a, uint32_t exclude_b, const VolumeTags& tags);

}  // namespace walkrad
