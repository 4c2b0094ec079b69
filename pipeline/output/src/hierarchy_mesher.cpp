#include "walkrad/output/hierarchy_mesher.h"

#include <memory>
#include "walkrad/output/surface_mesher.h"
#include "walkrad/hierarchical/point_radiosity.h"
#include "walkrad/scene/transmission_twins.h"

namespace walkrad {

SurfaceMesh mesh_hierarchy(const Hierarchy& h, double exposure, const PointSolution& point) {
  std::vector<MeshFace> faces;
  std::vector<uint32_t> leaf;
  for (uint32_t i = 0; i < h.nodes().size(); ++i) {
    const HNode& n = h[i];
    if (n.cluster || n.child_count) continue;
    faces.push_back({n.shape, n.normal, n.B, n.area, n.polygon});
    leaf.push_back(i);
  }
  if (!point.on) return mesh_faces(faces, exposure);
  // The mesher asks for a face's points one after another on one thread: the leaf's gather is kept
  // between them (LeafRadiosity), per thread; the clusters' part once for all (ClusterGather).
  const ClusterGather clusters(h, point.indirect, point.lights, point.rays);
  return mesh_faces(faces, exposure, [&](size_t face, const Vec3& x) {
    thread_local std::unique_ptr<LeafRadiosity> cached;
    thread_local const Hierarchy* cached_h = nullptr;
    thread_local uint32_t cached_leaf = UINT32_MAX;
    const uint32_t i = leaf[face];
    if (!cached || cached_h != &h || cached_leaf != i) {
      const bool transmitting = point.twins && (*point.twins)[h[i].polygon] != kNoTwin;
      cached = std::make_unique<LeafRadiosity>(clusters, i, transmitting);
      cached_h = &h;
      cached_leaf = i;
    }
    return cached->at(x);
  });
}

}  // namespace walkrad
