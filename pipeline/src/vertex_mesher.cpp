#include "walkrad/pipeline/vertex_mesher.h"

#include <algorithm>

#include "walkrad/pipeline/surface_mesher.h"

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
  std::vector<MeshFace> faces;
  faces.reserve(sub.elements.size());
  for (size_t e = 0; e < sub.elements.size(); ++e) {
    const Element& el = sub.elements[e];
    faces.push_back({el.shape, el.normal, radiosity[e], el.area, el.polygon});
  }
  return mesh_faces(faces, exposure);
}

}  // namespace walkrad
