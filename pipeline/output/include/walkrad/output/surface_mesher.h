// The bake's surface as a crack-free Gouraud mesh (algorithms.md §8; Baum, Mann, Smith & Winget 1991,
// "Making radiosity usable": T-vertices and anchoring). The faces are the solution's leaves
// (hierarchy leaves or uniform elements). Their corners are welded where positions coincide; where a
// face's edge passes through another face's corner (a finer neighbour's T-vertex, within this polygon
// or across polygons that share the edge), that vertex is inserted into the edge and the face is
// fanned from its centre. So no output edge has a vertex inside it: watertight, no cracks, no pixel
// dropouts, and both sides of a shared edge interpolate between the same two vertices.
//
// A vertex's radiosity is the area-weighted average over the faces that have it on their boundary (of
// their radiosity, or of the solution evaluated at the vertex from each face), within one smoothing group: polygons of one material, facing the same way, that touch (so a floor
// cut into several polygons is smooth across its cuts). At a crease or a material boundary each side
// keeps its own vertices: radiosity is discontinuous there physically.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "walkrad/core/huge_pages.h"
#include "walkrad/formats/scene.h"
#include "walkrad/formats/chunk.h"

namespace walkrad {

// A bake's whole surface before it is cut into chunks: the mesh, and per triangle its polygon.
struct SurfaceMesh {
  ChunkMesh mesh;
  std::vector<uint32_t> triangle_polygon;
};

// Appends one vertex: position, normal, radiosity B and its display colour B/π × exposure clamped to
// [0, 1] (glTF's range for COLOR_0). Shared by every mesher.
void append_vertex(ChunkMesh& mesh, const Vec3& position, const Vec3& normal, const Vec3& radiosity, double exposure);

struct MeshFace {
  Polygon shape;  // corners counter-clockwise seen from the front; shape.material is the face's material
  Vec3 normal;    // unit
  Vec3 radiosity; // B, W/m²
  Vec3 rho;       // reflectance (the final gather's direct light is reflected by it)
  double area = 0;
  uint32_t polygon = 0;  // the (contact-split) scene polygon it lies on
};
// On huge pages (core/huge_pages.h): a large level's faces are made afresh, page by page, twice.
using MeshFaces = HugeVector<MeshFace>;

// B at a point of face i (a corner nudged into the face, or its centre), where the solution can say
// more than its face's mean (point_radiosity.h); gathered: without the direct light, which the final
// gather evaluates at the vertex.
using FaceRadiosity = std::function<Vec3(size_t face, const Vec3& point, bool gathered)>;

// The final gather (final_gather.h): a vertex one of whose faces is seen takes, besides the faces'
// at(face, point, true), their mean ρ times direct(vertex, normal, its faces), evaluated once at the
// vertex itself; a fanned face's centre likewise when the face is seen.
struct VertexGather {
  std::function<bool(size_t face)> seen;
  std::function<Vec3(const Vec3& point, const Vec3& normal, const uint32_t* faces, size_t count)> direct;
};

// exposure: display colour = B/π × exposure, clamped to [0, 1]. at: when given, each vertex takes the
// area-weighted mean of at(face, point) over its faces instead of their mean radiosity; gather (with
// at): the final gather at the vertices it sees. Deterministic: the output depends only on the faces
// and their order.
// Under mpirun, the rank on which at(face, …) can be read (the one holding the links of its leaf:
// walkrad/hierarchical/link_owners.h); without it the faces are cut into blocks of equal cost.
using FaceRanks = std::function<int(size_t face)>;
// read, when given, is called once every reading of at is taken, before the vertices' direct light is
// gathered and the mesh written: what at reads may be freed then (a million-face level's links: 0.8 GB).
SurfaceMesh mesh_faces(const MeshFaces& faces, double exposure, const FaceRadiosity& at = {},
                       const VertexGather& gather = {}, const FaceRanks& face_rank = {},
                       const std::function<void()>& read = {});

}  // namespace walkrad
