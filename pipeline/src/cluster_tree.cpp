#include "walkrad/pipeline/cluster_tree.h"

#include <algorithm>

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
      node.area += polygon_area(scene.polygons[p]);
      cb.extend(centroid[p]);
    }
    if (count > max_leaf) {
      const Vec3 d = cb.diagonal();
      const int axis = d.x >= d.y && d.x >= d.z ? 0 : (d.y >= d.z ? 1 : 2);
      auto begin = tree.polygons.begin() + first, end = begin + count, mid = begin + count / 2;
      // Ties broken by polygon index: the tree does not depend on the sort's stability.
      std::nth_element(begin, mid, end, [&](uint32_t a, uint32_t b) {
        return centroid[a][axis] < centroid[b][axis] || (centroid[a][axis] == centroid[b][axis] && a < b);
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
  Builder b{scene, tree, std::vector<Vec3>(n), std::max(1u, max_leaf)};
  for (uint32_t i = 0; i < n; ++i) {
    tree.polygons[i] = i;
    tree.polygon_bounds[i] = polygon_bounds(scene.polygons[i]);
    b.centroid[i] = polygon_centroid(scene.polygons[i]);
  }
  tree.nodes.reserve(2 * (n / b.max_leaf + 1));
  if (n > 0) b.build(0, n);
  return tree;
}

}  // namespace walkrad
