#include "walkrad/output/hierarchy_mesher.h"

#include <memory>

#include <tbb/enumerable_thread_specific.h>

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
  struct Cached {
    uint32_t leaf = UINT32_MAX;
    std::unique_ptr<LeafRadiosity> radiosity;
  };
  tbb::enumerable_thread_specific<Cached> cache;  // lives no longer than `clusters`, which it refers to
  return mesh_faces(faces, exposure, [&](size_t face, const Vec3& x) {
    Cached& c = cache.local();
    const uint32_t i = leaf[face];
    if (c.leaf != i) {
      const bool transmitting = point.twins && (*point.twins)[h[i].polygon] != kNoTwin;
      c.radiosity = std::make_unique<LeafRadiosity>(clusters, i, transmitting);
      c.leaf = i;
    }
    return c.radiosity->at(x);
  });
}

}  // namespace walkrad
