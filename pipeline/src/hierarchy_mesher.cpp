#include "walkrad/pipeline/hierarchy_mesher.h"
#include "walkrad/pipeline/vertex_mesher.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace walkrad {

namespace {

bool contains(const HNode& e, const Vec3& p) {
  const Polygon& s = e.shape;
  for (int k = 0; k < s.count; ++k)
    if (dot(cross(s.v[(k + 1) % s.count] - s.v[k], p - s.v[k]), e.normal) < -1e-12) return false;
  return true;
}
}  // namespace

uint32_t leaf_at(const Hierarchy& h, uint32_t node, const Vec3& p) {
  while (h[node].child_count) {
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
  // Vertices keyed by (input polygon, position): leaves of one polygon share them; positions of a
  // shared corner are bit-identical since every midpoint is computed from the same two corners.
  using Key = std::tuple<uint32_t, double, double, double>;
  struct Acc {
    Vec3 sum;
    double area = 0;
    Vec3 normal;
    uint32_t index = 0;
  };
  std::map<Key, Acc> vertices;
  std::vector<uint32_t> leaves;
  for (uint32_t i = 0; i < h.nodes().size(); ++i) {
    const HNode& n = h[i];
    if (n.cluster || n.child_count) continue;
    leaves.push_back(i);
    for (int k = 0; k < n.shape.count; ++k) {
      Acc& a = vertices[Key(n.polygon, n.shape.v[k].x, n.shape.v[k].y, n.shape.v[k].z)];
      a.sum += n.B * n.area;
      a.area += n.area;
      a.normal = n.normal;
    }
  }
  SurfaceMesh surface;
  ChunkMesh& mesh = surface.mesh;
  uint32_t next = 0;
  for (auto& [key, a] : vertices) {
    a.index = next++;
    append_vertex(mesh, Vec3(std::get<1>(key), std::get<2>(key), std::get<3>(key)), a.normal, a.sum / a.area, exposure);
  }
  for (uint32_t i : leaves) {
    const HNode& n = h[i];
    uint32_t v[4];
    for (int k = 0; k < n.shape.count; ++k) v[k] = vertices[Key(n.polygon, n.shape.v[k].x, n.shape.v[k].y, n.shape.v[k].z)].index;
    mesh.indices.insert(mesh.indices.end(), {v[0], v[1], v[2]});
    if (n.shape.count == 4) mesh.indices.insert(mesh.indices.end(), {v[0], v[2], v[3]});
    surface.triangle_polygon.resize(mesh.triangle_count(), n.polygon);
  }
  return surface;
}

}  // namespace walkrad
