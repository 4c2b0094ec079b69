#include "walkrad/pipeline/hierarchy_mesher.h"
#include "walkrad/pipeline/surface_mesher.h"

#include <algorithm>

namespace walkrad {

namespace {

bool contains(const HNode& e, const Vec3& p) {
  const Polygon& s = e.shape;
  for (int k = 0; k < s.count; ++k)
    if (dot(cross(s.v[(k + 1) % s.count] - s.v[k], p - s.v[k]), e.normal) < -1e-12) return false;
  return true;
}
}  // namespace

uint32_t leaf_at(const Hierarchy& h, uint32_t node, const Vec3& p, int max_depth) {
  while (h[node].child_count && h[node].depth < max_depth) {
    uint32_t next = h.child(h[node], 0);
    for (uint32_t k = 0; k < h[node].child_count; ++k)
      if (contains(h[h.child(h[node], k)], p)) {
        next = h.child(h[node], k);
        break;
      }
    node = next;
  }
  return node;
}

SurfaceMesh mesh_hierarchy(const Hierarchy& h, double exposure) {
  std::vector<MeshFace> faces;
  for (const HNode& n : h.nodes())
    if (!n.cluster && !n.child_count) faces.push_back({n.shape, n.normal, n.B, n.area, n.polygon});
  return mesh_faces(faces, exposure);
}

}  // namespace walkrad
