#include "walkrad/scene/cluster_tree.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "walkrad/core/rounding.h"

namespace walkrad {

Bounds polygon_bounds(const Polygon& p) {
  Bounds b;
  for (int k = 0; k < p.count; ++k) b.extend(p.v[k]);
  return b;
}

namespace {

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

  int32_t build(uint32_t first, uint32_t count) {
    const int32_t index = int32_t(tree.nodes.size());
    tree.nodes.emplace_back();
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
      node.child[0] = build(first, count / 2);
      node.child[1] = build(first + count / 2, count - count / 2);
    }
    tree.nodes[index] = node;
    return index;
  }
};

}  // namespace

ClusterTree build_cluster_tree(const Scene& scene, uint32_t max_leaf) {
  ClusterTree tree;
  const uint32_t n = uint32_t(scene.polygons.size());
  tree.polygons.resize(n);
  tree.polygon_bounds.resize(n);
  Builder b{scene, tree, std::vector<Vec3>(n), std::max(1u, max_leaf), Vec3{}, 0.0, std::vector<double>(n), {}};
  for (uint32_t i = 0; i < n; ++i) {
    tree.polygons[i] = i;
    tree.polygon_bounds[i] = polygon_bounds(scene.polygons[i]);
    b.centroid[i] = polygon_centroid(scene.polygons[i]);
    b.area[i] = polygon_area(scene.polygons[i]);
  }
  Bounds all;
  for (uint32_t i = 0; i < n; ++i) all.extend(tree.polygon_bounds[i]);
  if (n > 0) {
    b.origin = all.lo;
    b.quantum = std::max(1e-9 * length(all.diagonal()) + rounding_at(all.lo) + rounding_at(all.hi), 1e-300);
  }
  b.key.resize(n);
  for (uint32_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) b.key[i][size_t(a)] = b.steps(b.centroid[i][a] - b.origin[a]);
  tree.nodes.reserve(2 * (n / b.max_leaf + 1));
  if (n > 0) b.build(0, n);
  tree.slot.resize(n);
  for (uint32_t i = 0; i < n; ++i) tree.slot[tree.polygons[i]] = i;
  return tree;
}

}  // namespace walkrad
