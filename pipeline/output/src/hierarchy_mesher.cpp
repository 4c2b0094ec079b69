#include "walkrad/output/hierarchy_mesher.h"
#include "walkrad/output/surface_mesher.h"

namespace walkrad {

SurfaceMesh mesh_hierarchy(const Hierarchy& h, double exposure) {
  std::vector<MeshFace> faces;
  for (const HNode& n : h.nodes())
    if (!n.cluster && !n.child_count) faces.push_back({n.shape, n.normal, n.B, n.area, n.polygon});
  return mesh_faces(faces, exposure);
}

}  // namespace walkrad
