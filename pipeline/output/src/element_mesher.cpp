#include "walkrad/output/element_mesher.h"

namespace walkrad {

SurfaceMesh mesh_elements(const Subdivision& sub, const std::vector<Vec3>& radiosity, double exposure) {
  MeshFaces faces;
  faces.reserve(sub.elements.size());
  for (size_t e = 0; e < sub.elements.size(); ++e) {
    const Element& el = sub.elements[e];
    faces.push_back({el.shape, el.normal, radiosity[e], {}, el.area, el.polygon});
  }
  return mesh_faces(faces, exposure);
}

}  // namespace walkrad
