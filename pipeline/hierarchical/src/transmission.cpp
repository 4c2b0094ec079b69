#include "walkrad/hierarchical/transmission.h"

namespace walkrad {

namespace {

// Area-weighted sum over node's leaves of H + D (links: with the links' part), or of D alone.
Vec3 mean_received(const Hierarchy& h, uint32_t node, bool links, double& area) {
  const HNode& n = h[node];
  if (n.child_count == 0) {
    area = n.area;
    return ((links ? n.Hl : Vec3{}) + n.D) * n.area;
  }
  Vec3 sum;
  area = 0;
  for (uint32_t k = 0; k < n.child_count; ++k) {
    double a = 0;
    sum += mean_received(h, h.child(n, k), links, a);
    area += a;
  }
  return sum;
}

Vec3 twin_mean(const Hierarchy& h, const HNode& leaf, uint32_t twin_polygon, bool links) {
  double area = 0;
  const Vec3 sum = mean_received(h, twin_node(h, leaf, twin_polygon), links, area);
  return area > 0 ? sum / area : Vec3{};
}

}  // namespace

uint32_t twin_node(const Hierarchy& h, const HNode& leaf, uint32_t twin_polygon) {
  return leaf_at(h, h.polygon_root(twin_polygon), polygon_centroid(leaf.shape), leaf.depth);
}

Vec3 material_transmittance(const Hierarchy& h, const HNode& element) {
  return h.scene().materials[h.scene().polygons[element.polygon].material].transmittance;
}

Vec3 twin_received(const Hierarchy& h, const HNode& leaf, uint32_t twin_polygon) { return twin_mean(h, leaf, twin_polygon, true); }

Vec3 twin_direct(const Hierarchy& h, const HNode& leaf, uint32_t twin_polygon) { return twin_mean(h, leaf, twin_polygon, false); }

}  // namespace walkrad
