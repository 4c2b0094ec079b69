// Cutting a bake's surface into streamable chunks: the cluster hierarchy is cut top-down
// where a node holds at most max_triangles output triangles, so each chunk is a spatially compact
// group of whole input polygons (a room's furniture stays with its room when the building's
// hierarchy follows its rooms). Chunks come in depth-first order of the tree: deterministic.
//
// Per chunk and per viewpoint, its importance for streaming: the fraction of the viewpoint's image
// (cos³-weighted pixels, the solid angle) that sees the chunk. A runtime loads first the chunks that
// the viewpoints ahead of the camera see most.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/chunk.h"
#include "walkrad/formats/scene.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/output/surface_mesher.h"

namespace walkrad {

struct ChunkCut {
  std::vector<ChunkMesh> meshes;
  std::vector<uint32_t> polygon_chunk;  // per polygon of the tree's scene: its chunk
};

// max_triangles ≥ 1. A single leaf cluster larger than max_triangles stays one chunk.
ChunkCut cut_into_chunks(const SurfaceMesh& surface, const ClusterTree& tree, uint64_t max_triangles);

// importance[c][v]: fraction of viewpoint v's image covered by chunk c (grid² primary rays per view).
std::vector<std::vector<float>> chunk_importance(const std::vector<Viewpoint>& views, const RayScene& rays,
                                                 const std::vector<uint32_t>& polygon_chunk, size_t chunks, int grid,
                                                 uint64_t& rays_cast);

}  // namespace walkrad
