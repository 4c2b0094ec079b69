#include "walkrad/output/hierarchy_mesher.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "walkrad/output/discontinuity_mesh.h"
#include "walkrad/output/surface_mesher.h"
#include "walkrad/hierarchical/final_gather.h"
#include "walkrad/hierarchical/link_owners.h"
#include "walkrad/hierarchical/point_radiosity.h"
#include "walkrad/scene/contact_split.h"
#include "walkrad/scene/transmission_twins.h"

namespace walkrad {

namespace {
constexpr uint32_t kNoEmitter = UINT32_MAX;  // a cut that no emitter draws (a contact band)

// Discontinuity meshing (discontinuity_mesh.h): the seen faces cut along the shadow boundaries of their
// emitters, within as many expected crossings as an eighth of the faces (at least 1,024). The pieces
// replace the faces, with their leaves and candidate emitters.
void cut_along_boundaries(const Hierarchy& h, const DirectGather& direct, const PointSolution& point,
                          const std::vector<uint8_t>& seen_face, MeshFaces& faces, std::vector<uint32_t>& leaf,
                          std::vector<EmitterRanges>& candidates) {
  BoundarySelection chosen =
      select_boundaries(h, direct, faces, seen_face, candidates, std::max<uint64_t>(faces.size() / 8, 1024), point.rays);
  if (point.counts) {
    point.counts->found = chosen.found;
    point.counts->hidden = chosen.hidden;
    point.counts->drawn = chosen.segments;
  }
  // And along the near-contact bands beside covers (contact_split.h), outside the budget: four
  // segments a cover, wherever the walkthrough sees the polygon under it.
  std::vector<uint8_t> seen_polygon(h.scene().polygons.size(), 0);
  for (size_t f = 0; f < faces.size(); ++f) seen_polygon[faces[f].polygon] |= seen_face[f];
  const std::vector<std::vector<ContactBand>> bands = contact_bands(h.scene(), h.tree(), seen_polygon);
  uint64_t banded = 0;
  for (size_t p = 0; p < bands.size(); ++p)
    for (const ContactBand& b : bands[p]) {
      chosen.by_polygon[p].push_back({b.a, b.b, b.a});
      chosen.emitter[p].push_back(kNoEmitter);
      ++banded;
    }
  if (point.counts) point.counts->contact_bands = banded;
  if (chosen.segments + banded) {
    // Four times the chunks' position error (--position-tolerance, 1e-5 of the diagonal by
    // default; the mesher welds within 1e-6): a vertex and an edge each move by up to √3 of it, so
    // anything closer could meet in the chunks.
    const double snap = 4 * std::max(point.position_error, 1e-6) * length(h.scene().bounds().diagonal());
    CutFaces cut = cut_faces(faces, chosen.by_polygon, snap);
    if (point.counts)
      for (const auto& applied : cut.applied) point.counts->faces_cut += !applied.empty();
    std::vector<uint32_t> cut_leaf(cut.from.size());
    std::vector<EmitterRanges> cut_candidates(cut.from.size());
    tbb::parallel_for(size_t(0), cut.from.size(), [&](size_t k) {
      cut_leaf[k] = leaf[cut.from[k]];
      // A piece gathers the emitters whose boundaries cut its face too: a leaf the solution found
      // wholly hidden from the lamp (no link to it) lies partly in its penumbra once cut there.
      const uint32_t f = cut.from[k];
      cut_candidates[k] = candidates[f];
      for (uint32_t g : cut.applied[f]) {
        const uint32_t e = chosen.emitter[faces[f].polygon][g];
        if (e != kNoEmitter) merge_ranges(cut_candidates[k], {{e, e + 1}});
      }
    });
    faces.swap(cut.faces);
    leaf.swap(cut_leaf);
    candidates.swap(cut_candidates);
  }
}

}  // namespace

SurfaceMesh mesh_hierarchy(const Hierarchy& h, double exposure, const PointSolution& point) {
  // The leaves, made to their count (a large level's array of faces grown by doubling is copied and
  // faulted in twice over).
  std::vector<uint32_t> leaf;
  for (uint32_t i = 0; i < h.nodes().size(); ++i)
    if (!h[i].cluster && !h[i].child_count) leaf.push_back(i);
  MeshFaces faces(leaf.size());
  tbb::parallel_for(size_t(0), leaf.size(), [&](size_t f) {
    const HNode& n = h[leaf[f]];
    faces[f] = {n.shape, n.normal, n.B, n.rho, n.area, n.polygon};
  });
  if (!point.on) return mesh_faces(faces, exposure);
  // The mesher asks for a face's points one after another on one thread: the leaf's gather is kept
  // between them (LeafRadiosity), per thread; the clusters' part once for all (ClusterGather).
  ClusterGather clusters(h, point.indirect, point.lights, point.rays);
  struct Cached {
    uint32_t leaf = UINT32_MAX;
    std::unique_ptr<LeafRadiosity> radiosity;
    ChainReadings chain;  // the last leaf's ancestors' link readings (siblings come one after another)
  };
  tbb::enumerable_thread_specific<Cached> cache;  // lives no longer than `clusters`, which it refers to
  auto transmitting = [&](uint32_t polygon) { return point.twins && (*point.twins)[polygon] != kNoTwin; };
  // The final gather: the emitters each seen face's leaf can receive from (final_gather.h).
  VertexGather gather;
  std::unique_ptr<DirectGather> direct;
  std::vector<EmitterRanges> candidates;
  if (point.gather) {
    direct = std::make_unique<DirectGather>(h, point.lights, point.rays);
    const double reach = view_reach(h);
    auto seen = [&](size_t face) {
      const uint32_t p = faces[face].polygon;
      return (!point.seen || (*point.seen)[p]) && !transmitting(p) && in_view(h, leaf[face], reach);
    };
    candidates.resize(faces.size());
    std::vector<uint8_t> seen_face(faces.size());
    for (size_t f = 0; f < faces.size(); ++f) seen_face[f] = seen(f);
    // Each on the rank holding the leaf's links (link_owners.h), given to every rank: a vertex's
    // direct light merges the candidates of its faces, whatever their polygons.
    tbb::parallel_for(size_t(0), faces.size(), [&](size_t f) {
      if (seen_face[f] && h.owners().holds_polygon(faces[f].polygon)) candidates[f] = direct->candidates(leaf[f]);
    });
    if (h.owners().divided())
      share_owned_lists(candidates, [&](size_t f) { return seen_face[f] ? polygon_rank(h, faces[f].polygon) : -1; });
    // The seen leaves' close sources taken part by part (ClusterGather::resolve_close_sources).
    std::vector<uint32_t> seen_leaves;
    for (size_t f = 0; f < faces.size(); ++f)
      if (seen_face[f]) seen_leaves.push_back(leaf[f]);
    clusters.resolve_close_sources(seen_leaves, point.twins);
    if (point.discontinuities && direct->emitter_count())
      cut_along_boundaries(h, *direct, point, seen_face, faces, leaf, candidates);
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
  // A face's points are read from its leaf's links: on their rank, when the links are divided.
  FaceRanks face_rank;
  if (h.owners().divided()) face_rank = [&](size_t face) { return polygon_rank(h, faces[face].polygon); };
  return mesh_faces(faces, exposure, [&](size_t face, const Vec3& x, bool gathered) {
    Cached& c = cache.local();
    const uint32_t i = leaf[face];
    if (c.leaf != i) {
      c.radiosity = std::make_unique<LeafRadiosity>(clusters, i, point.twins ? (*point.twins)[h[i].polygon] : kNoTwin, &c.chain);
      c.leaf = i;
    }
    return c.radiosity->at(x, gathered);
  }, gather, face_rank, [&] {
    cache.clear();  // the leaves' readings, and what they read
    if (point.read) point.read();
  });
}

}  // namespace walkrad
