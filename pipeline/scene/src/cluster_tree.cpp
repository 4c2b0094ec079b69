#include "walkrad/scene/cluster_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "walkrad/core/rounding.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

namespace walkrad {

Bounds polygon_bounds(const Polygon& p) {
  Bounds b;
  for (int k = 0; k < p.count; ++k) b.extend(p.v[k]);
  return b;
}

namespace {

constexpr uint32_t kParallelBuild = 16384;  // polygons under a node whose halves go to two threads

struct Builder {
  const Scene& scene;
  ClusterTree& tree;
  std::vector<Vec3> centroid;
  uint32_t max_leaf;
  Vec3 origin{};          // the scene's lower corner
  double quantum = 0;     // positions and extents are compared in steps of this (see build)
  // Per polygon, worked out once rather than at every level of the tree: its area and its
  // centroid's steps from the origin on each axis.
  std::vector<double> area;
  std::vector<std::array<long long, 3>> key;

  long long steps(double x) const { return std::llround(x / quantum); }

  // Nodes below (and with) a node over `count` polygons, by count: the split depends on the count
  // alone, and a level's counts differ by 1 at most (a few entries, filled before the build).
  std::map<uint32_t, size_t> sizes;
  size_t count_nodes(uint32_t count) {
    if (const auto it = sizes.find(count); it != sizes.end()) return it->second;
    const size_t n = count > max_leaf ? 1 + count_nodes(count / 2) + count_nodes(count - count / 2) : 1;
    return sizes[count] = n;
  }
  size_t subtree(uint32_t count) const { return sizes.at(count); }

  // The node at `index` (depth first, child 0 first: its subtree fills [index, index + subtree)).
  // Halves of many polygons are built on two threads: they touch disjoint polygons and nodes, and
  // each node's index is fixed by the counts, so the tree is the one a single thread builds.
  void build(uint32_t first, uint32_t count, int32_t index) {
    ClusterNode node;
    node.first = first;
    node.count = count;
    Bounds cb;
    for (uint32_t i = first; i < first + count; ++i) {
      const uint32_t p = tree.polygons[i];
      node.bounds.extend(tree.polygon_bounds[p]);
      node.area += area[p];
      cb.extend(centroid[p]);
    }
    if (count > max_leaf) {
      // Extents and centroids compared in steps of 1e-9 of the scene (plus rounding at its
      // coordinates), relative to its corner: a cube's equal sides, or centroids in one plane, stay
      // tied when the scene is scaled or moved and its last bits change, so the tree (and with it
      // the hierarchical solution) does not (docs/numerics.md).
      const Vec3 d = cb.diagonal();
      const long long dx = steps(d.x), dy = steps(d.y), dz = steps(d.z);
      const int axis = dx >= dy && dx >= dz ? 0 : (dy >= dz ? 1 : 2);
      auto begin = tree.polygons.begin() + first, end = begin + count, mid = begin + count / 2;
      // Ties broken by polygon index: the tree does not depend on the sort's stability.
      std::nth_element(begin, mid, end, [&](uint32_t a, uint32_t b) {
        const long long ka = key[a][size_t(axis)], kb = key[b][size_t(axis)];
        return ka < kb || (ka == kb && a < b);
      });
      node.child[0] = index + 1;
      node.child[1] = int32_t(index + 1 + subtree(count / 2));
      auto low = [&] { build(first, count / 2, node.child[0]); };
      auto high = [&] { build(first + count / 2, count - count / 2, node.child[1]); };
      if (count >= kParallelBuild) {
        tbb::parallel_invoke(low, high);
      } else {
        low();
        high();
      }
    }
    tree.nodes[size_t(index)] = node;
  }
};

}  // namespace

ClusterTree build_cluster_tree(const Scene& scene, uint32_t max_leaf) {
  ClusterTree tree;
  const uint32_t n = uint32_t(scene.polygons.size());
  tree.polygons.resize(n);
  tree.polygon_bounds.resize(n);
  Builder b{scene, tree, std::vector<Vec3>(n), std::max(1u, max_leaf), Vec3{}, 0.0, std::vector<double>(n), {}};
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 4096), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t i = r.begin(); i != r.end(); ++i) {
      tree.polygons[i] = i;
      tree.polygon_bounds[i] = polygon_bounds(scene.polygons[i]);
      b.centroid[i] = polygon_centroid(scene.polygons[i]);
      b.area[i] = polygon_area(scene.polygons[i]);
    }
  });
  Bounds all;
  for (uint32_t i = 0; i < n; ++i) all.extend(tree.polygon_bounds[i]);
  if (n > 0) {
    b.origin = all.lo;
    b.quantum = std::max(1e-9 * length(all.diagonal()) + rounding_at(all.lo) + rounding_at(all.hi), 1e-300);
  }
  b.key.resize(n);
  for (uint32_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) b.key[i][size_t(a)] = b.steps(b.centroid[i][a] - b.origin[a]);
  if (n > 0) {
    tree.nodes.resize(b.count_nodes(n));
    b.build(0, n, 0);
  }
  tree.slot.resize(n);
  for (uint32_t i = 0; i < n; ++i) tree.slot[tree.polygons[i]] = i;
  return tree;
}

}  // namespace walkrad
