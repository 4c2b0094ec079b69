#include "walkrad/output/hierarchy_mesher.h"

#include <cmath>
#include <memory>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "walkrad/output/surface_mesher.h"
#include "walkrad/hierarchical/final_gather.h"
#include "walkrad/hierarchical/point_radiosity.h"
#include "walkrad/scene/transmission_twins.h"

namespace walkrad {

SurfaceMesh mesh_hierarchy(const Hierarchy& h, double exposure, const PointSolution& point) {
  std::vector<MeshFace> faces;
  std::vector<uint32_t> leaf;
  for (uint32_t i = 0; i < h.nodes().size(); ++i) {
    const HNode& n = h[i];
    if (n.cluster || n.child_count) continue;
    faces.push_back({n.shape, n.normal, n.B, n.rho, n.area, n.polygon});
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
  auto transmitting = [&](uint32_t polygon) { return point.twins && (*point.twins)[polygon] != kNoTwin; };
  // The final gather: the emitters each seen face's leaf can receive from (final_gather.h).
  VertexGather gather;
  std::unique_ptr<DirectGather> direct;
  std::vector<EmitterRanges> candidates;
  if (point.gather) {
    direct = std::make_unique<DirectGather>(h, point.lights, point.rays);
    auto seen = [&](size_t face) {
      const uint32_t p = faces[face].polygon;
      return (!point.seen || (*point.seen)[p]) && !transmitting(p);
    };
    candidates.resize(faces.size());
    tbb::parallel_for(size_t(0), faces.size(), [&](size_t f) {
      if (seen(f)) candidates[f] = direct->candidates(leaf[f]);
    });
    gather.seen = seen;
    gather.direct = [&](const Vec3& x, const Vec3& normal, const uint32_t* around, size_t count) {
      EmitterRanges from = candidates[around[0]];
      Vec3 centre = polygon_centroid(faces[around[0]].shape);
      for (size_t k = 1; k < count; ++k) {
        merge_ranges(from, candidates[around[k]]);
        centre += polygon_centroid(faces[around[k]].shape);
      }
      // Towards the faces around x: zero where they surround it.
      Vec3 inward = centre / double(count) - x;
      inward = inward - normal * dot(inward, normal);
      const double len = length(inward);
      inward = len > 1e-3 * std::sqrt(faces[around[0]].area) ? inward / len : Vec3{};
      uint64_t rays = 0;
      return direct->at(x, normal, inward, from, rays);
    };
  }
  return mesh_faces(faces, exposure, [&](size_t face, const Vec3& x, bool gathered) {
    Cached& c = cache.local();
    const uint32_t i = leaf[face];
    if (c.leaf != i) {
      c.radiosity = std::make_unique<LeafRadiosity>(clusters, i, point.twins ? (*point.twins)[h[i].polygon] : kNoTwin);
      c.leaf = i;
    }
    return c.radiosity->at(x, gathered);
  }, gather);
}

}  // namespace walkrad
