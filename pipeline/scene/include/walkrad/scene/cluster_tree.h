// ClusterTree: a bounding volume hierarchy over the input polygons, from one root cluster down to
// leaves of a few polygons. It serves shaft culling (Haines & Wallace 1991: which polygons can stand
// between two nodes) and is the cluster level of hierarchical radiosity (Smits, Arvo & Greenberg
// 1994; Sillion 1995): a cluster's total one-sided area A and its volume V give its extinction
// κ = A / 4V (algorithms.md §7).
//
// Built top-down by splitting at the median polygon centroid along the longest axis: deterministic,
// balanced, O(n log n).
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/scene.h"

namespace walkrad {

struct ClusterNode {
  Bounds bounds;
  double area = 0;          // total one-sided area of the polygons below
  uint32_t first = 0;       // polygons below: ClusterTree::polygons[first, first + count)
  uint32_t count = 0;
  int32_t child[2] = {-1, -1};  // both -1 for a leaf; child 0 holds polygons [first, first + count / 2)
  bool leaf() const { return child[0] < 0; }
};

struct ClusterTree {
  std::vector<ClusterNode> nodes;   // nodes[0] is the root
  std::vector<uint32_t> polygons;   // polygon indices, permuted so every node's are contiguous
  std::vector<Bounds> polygon_bounds;  // per polygon (by polygon index)
  std::vector<uint32_t> slot;       // per polygon: its place in `polygons` (under node n iff in [first, first + count))
};

// max_leaf: polygons per leaf (at least 1).
ClusterTree build_cluster_tree(const Scene& scene, uint32_t max_leaf = 4);

Bounds polygon_bounds(const Polygon& p);

}  // namespace walkrad
