#include "walkrad/output/chunking.h"

#include <algorithm>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "walkrad/visibility/view_grid.h"

namespace walkrad {

ChunkCut cut_into_chunks(const SurfaceMesh& surface, const ClusterTree& tree, uint64_t max_triangles) {
  max_triangles = std::max<uint64_t>(max_triangles, 1);
  std::vector<uint64_t> polygon_triangles(tree.polygon_bounds.size(), 0);
  for (uint32_t p : surface.triangle_polygon) ++polygon_triangles[p];
  // Triangles below each node: children come after their parents, so sum bottom-up.
  std::vector<uint64_t> below(tree.nodes.size(), 0);
  for (size_t i = tree.nodes.size(); i-- > 0;) {
    const ClusterNode& n = tree.nodes[i];
    if (n.leaf())
      for (uint32_t k = n.first; k < n.first + n.count; ++k) below[i] += polygon_triangles[tree.polygons[k]];
    else
      below[i] = below[size_t(n.child[0])] + below[size_t(n.child[1])];
  }

  ChunkCut cut;
  cut.polygon_chunk.assign(tree.polygon_bounds.size(), 0);
  uint32_t chunks = 0;
  std::vector<int32_t> stack{0};
  while (!stack.empty()) {
    const int32_t i = stack.back();
    stack.pop_back();
    const ClusterNode& n = tree.nodes[size_t(i)];
    if (below[size_t(i)] == 0) continue;  // nothing meshed here (no triangles)
    if (below[size_t(i)] > max_triangles && !n.leaf()) {
      stack.push_back(n.child[1]);  // depth first, child 0 first
      stack.push_back(n.child[0]);
      continue;
    }
    for (uint32_t k = n.first; k < n.first + n.count; ++k) cut.polygon_chunk[tree.polygons[k]] = chunks;
    ++chunks;
  }

  // Copy each chunk's triangles, renumbering its vertices in order of first use.
  const ChunkMesh& m = surface.mesh;
  cut.meshes.resize(chunks);
  std::vector<uint32_t> remap(m.vertex_count(), UINT32_MAX);
  std::vector<uint32_t> owner(m.vertex_count(), UINT32_MAX);
  // Triangles grouped by chunk (stable), so that a chunk's triangles are visited together.
  std::vector<size_t> order(surface.triangle_polygon.size());
  for (size_t t = 0; t < order.size(); ++t) order[t] = t;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return cut.polygon_chunk[surface.triangle_polygon[a]] < cut.polygon_chunk[surface.triangle_polygon[b]];
  });
  for (size_t t : order) {
    const uint32_t c = cut.polygon_chunk[surface.triangle_polygon[t]];
    ChunkMesh& out = cut.meshes[c];
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = m.indices[3 * t + size_t(k)];
      if (owner[v] != c) {  // first use in this chunk (vertices on a chunk border are copied)
        owner[v] = c;
        remap[v] = uint32_t(out.vertex_count());
        for (int a = 0; a < 3; ++a) {
          out.positions.push_back(m.positions[3 * v + size_t(a)]);
          out.normals.push_back(m.normals[3 * v + size_t(a)]);
          out.colors.push_back(m.colors[3 * v + size_t(a)]);
          out.radiosity.push_back(m.radiosity[3 * v + size_t(a)]);
        }
      }
      out.indices.push_back(remap[v]);
    }
  }
  return cut;
}

std::vector<std::vector<float>> chunk_importance(const std::vector<Viewpoint>& views, const RayScene& rays,
                                                 const std::vector<uint32_t>& polygon_chunk, size_t chunks, int grid,
                                                 uint64_t& rays_cast) {
  std::vector<std::vector<float>> importance(chunks, std::vector<float>(views.size(), 0.0f));
  if (views.empty()) return importance;
  // Every viewpoint (no subset), each on its own, its hits kept as (chunk, weight) in a list per
  // thread that is reused from view to view: listed afresh for a batch of 16 views (cast_view_rays,
  // 48 B × grid² a view), their fresh pages would be most of this phase on office-floor's 8 rooms. A
  // hit's weight is its share of its view over the size of its batch of 16, as cast_view_rays gives
  // it: the same bits.
  constexpr size_t kBatch = 16;
  const size_t V = views.size();
  std::vector<double> sum(V * chunks, 0.0);  // by view, then chunk
  tbb::parallel_for(size_t(0), V, [&](size_t v) {  // each view writes its own row
    thread_local std::vector<std::pair<uint32_t, double>> hits;
    hits.clear();
    const double total = cast_view_grid(views[v], rays, grid, [&](const RayScene::Hit& hit, double weight) {
      hits.push_back({polygon_chunk[hit.polygon], weight});
    });
    const double batch = double(std::min(v / kBatch * kBatch + kBatch, V) - v / kBatch * kBatch);
    for (const auto& [chunk, weight] : hits) sum[v * chunks + chunk] += weight / (total * batch) * batch;
  });
  rays_cast += uint64_t(V) * uint64_t(grid) * uint64_t(grid);
  for (size_t c = 0; c < chunks; ++c)
    for (size_t v = 0; v < V; ++v) importance[c][v] = float(sum[v * chunks + c]);
  return importance;
}

}  // namespace walkrad
