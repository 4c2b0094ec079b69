#include "walkrad/hierarchical/transmission.h"

namespace walkrad {

namespace {

Vec3 mean_received(const Hierarchy& h, uint32_t node, double& area) {
  const HNode& n = h[node];
  if (n.child_count == 0) {
    area = n.area;
    return (n.Hl + n.D) * n.area;
  }
  Vec3 sum;
  area = 0;
  for (uint32_t k = 0; k < n.child_count; ++k) {
    double a = 0;
    sum += mean_received(h, h.child(n, k), a);
    area += a;
  }
  return sum;
}

}  // namespace

Vec3 twin_received(const Hierarchy& h, const HNode& leaf, uint32_t twin_polygon) {
  const uint32_t node = leaf_at(h, h.polygon_root(twin_polygon), polygon_centroid(leaf.shape), leaf.depth);
  double area = 0;
  const Vec3 sum = mean_received(h, node, area);
  return area > 0 ? sum / area : Vec3{};
}

}  // namespace walkrad
