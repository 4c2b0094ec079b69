#include "walkrad/pipeline/vertex_mesher.h"

#include <algorithm>

namespace walkrad {


void append_vertex(ChunkMesh& mesh, const Vec3& position, const Vec3& normal, const Vec3& radiosity, double exposure) {
  const Vec3 colour = radiosity * (exposure / kPi);
  for (int k = 0; k < 3; ++k) {
    mesh.positions.push_back(float(position[k]));
    mesh.normals.push_back(float(normal[k]));
    mesh.radiosity.push_back(float(radiosity[k]));
    mesh.colors.push_back(float(std::clamp(colour[k], 0.0, 1.0)));
  }
}

SurfaceMesh mesh_elements(const Subdivision& sub, const std::vector<Vec3>& radiosity, double exposure) {
  // Grid vertices belong to one polygon, so averaging over the elements that name a vertex stays
  // inside that polygon.
  std::vector<Vec3> sum(sub.vertices.size());
  std::vector<double> weight(sub.vertices.size(), 0.0);
  std::vector<Vec3> normal(sub.vertices.size());
  for (size_t e = 0; e < sub.elements.size(); ++e) {
    const Element& el = sub.elements[e];
    for (int k = 0; k < el.shape.count; ++k) {
      sum[el.corner[k]] += radiosity[e] * el.area;
      weight[el.corner[k]] += el.area;
      normal[el.corner[k]] = el.normal;
    }
  }

  // Keep only vertices some element uses, renumbered in order (deterministic).
  std::vector<uint32_t> remap(sub.vertices.size(), UINT32_MAX);
  SurfaceMesh surface;
  ChunkMesh& mesh = surface.mesh;
  for (size_t v = 0; v < sub.vertices.size(); ++v) {
    if (weight[v] <= 0) continue;
    remap[v] = uint32_t(mesh.vertex_count());
    append_vertex(mesh, sub.vertices[v], normal[v], sum[v] / weight[v], exposure);
  }
  for (const Element& el : sub.elements) {
    const auto& c = el.corner;
    mesh.indices.insert(mesh.indices.end(), {remap[c[0]], remap[c[1]], remap[c[2]]});
    if (el.shape.count == 4) mesh.indices.insert(mesh.indices.end(), {remap[c[0]], remap[c[2]], remap[c[3]]});
    surface.triangle_polygon.resize(mesh.triangle_count(), el.polygon);
  }
  return surface;
}

}  // namespace walkrad
