// From the classic method's elements to a displayable mesh: the elements are the faces of the
// crack-free Gouraud mesh of surface_mesher.h. Also the vertex writer every mesher shares.
#pragma once

#include <vector>

#include "walkrad/formats/chunk.h"
#include "walkrad/pipeline/subdivision.h"

namespace walkrad {

// A bake's whole surface before it is cut into chunks: the mesh, and per triangle its polygon.
struct SurfaceMesh {
  ChunkMesh mesh;
  std::vector<uint32_t> triangle_polygon;
};

// Appends one vertex: position, normal, radiosity B and its display colour B/π × exposure clamped to
// [0, 1] (glTF's range for COLOR_0). Shared by every mesher.
void append_vertex(ChunkMesh& mesh, const Vec3& position, const Vec3& normal, const Vec3& radiosity, double exposure);

// radiosity: B per element. exposure: display colour = B/π × exposure, clamped to [0, 1] (what a
// display shows; lights saturate). _RADIOSITY keeps the unclamped physical value.
SurfaceMesh mesh_elements(const Subdivision& sub, const std::vector<Vec3>& radiosity, double exposure);

}  // namespace walkrad
