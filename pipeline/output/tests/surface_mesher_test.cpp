// The crack-free mesher: T-vertices anchored, smooth across polygons of one surface, sharp at creases
// and material boundaries.
#include "walkrad/output/surface_mesher.h"

#include <gtest/gtest.h>

#include "walkrad/testing/mesh_checks.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

MeshFace face(Vec3 a, Vec3 b, Vec3 c, Vec3 d, double radiosity, uint32_t polygon, uint32_t material = 0) {
  MeshFace f;
  f.shape = test::quad(a, b, c, d, material);
  f.normal = polygon_normal(f.shape);
  f.radiosity = Vec3(radiosity, radiosity, radiosity);
  f.area = polygon_area(f.shape);
  f.polygon = polygon;
  return f;
}

// The unit square [x0, x0+s]×[y0, y0+s] in the plane z = 0, facing +z.
MeshFace square(double x0, double y0, double s, double radiosity, uint32_t polygon, uint32_t material = 0) {
  return face({x0, y0, 0}, {x0 + s, y0, 0}, {x0 + s, y0 + s, 0}, {x0, y0 + s, 0}, radiosity, polygon, material);
}

// A coarse square beside a finer one, as two polygons of one material (a floor cut in two).
MeshFaces coarse_beside_fine(uint32_t right_material = 0) {
  return {square(0, 0, 1, 1.0, 0), square(1, 0, 0.5, 2.0, 1, right_material), square(1.5, 0, 0.5, 3.0, 1, right_material),
          square(1, 0.5, 0.5, 4.0, 1, right_material), square(1.5, 0.5, 0.5, 5.0, 1, right_material)};
}

TEST(MeshChecks, FindATJunction) {  // the check itself can fail
  ChunkMesh m;
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.5, 0, 0), Vec3(1, -1, 0)})
    append_vertex(m, p, Vec3(0, 0, 1), Vec3(1, 1, 1), 1.0);
  m.indices = {0, 1, 2, 0, 4, 3};  // vertex 3 lies inside edge 0–1
  EXPECT_EQ(test::count_t_junctions(m, 1e-9), 1u);
}

TEST(SurfaceMesher, AnchorsTheFinerNeighboursVerticesInTheCoarseFace) {
  const SurfaceMesh s = mesh_faces(coarse_beside_fine(), 1.0);
  EXPECT_EQ(test::count_t_junctions(s.mesh, 1e-9), 0u);
  EXPECT_EQ(test::largest_colour_seam(s.mesh, 1e-9), 0.0);  // one vertex per position: shared, one value
  // The T-vertex (1, 0.5) averages the coarse face and the two fine faces beside it, by area.
  bool seen = false;
  for (size_t v = 0; v < s.mesh.vertex_count(); ++v)
    if (length(test::vertex_position(s.mesh, v) - Vec3(1, 0.5, 0)) < 1e-9) {
      EXPECT_NEAR(s.mesh.radiosity[3 * v], (1.0 * 1.0 + 0.25 * 2.0 + 0.25 * 4.0) / 1.5, 1e-6);
      seen = true;
    }
  EXPECT_TRUE(seen);
  // Every face's triangles stay in its polygon, and cover its area.
  ASSERT_EQ(s.triangle_polygon.size(), s.mesh.triangle_count());
  double area[2] = {0, 0};
  for (size_t t = 0; t < s.mesh.triangle_count(); ++t) {
    const Vec3 a = test::vertex_position(s.mesh, s.mesh.indices[3 * t]), b = test::vertex_position(s.mesh, s.mesh.indices[3 * t + 1]),
               c = test::vertex_position(s.mesh, s.mesh.indices[3 * t + 2]);
    const Vec3 n = cross(b - a, c - a);
    EXPECT_GT(n.z, 0) << "triangle " << t << " is degenerate or faces away";
    area[s.triangle_polygon[t]] += 0.5 * length(n);
  }
  EXPECT_NEAR(area[0], 1.0, 1e-12);
  EXPECT_NEAR(area[1], 1.0, 1e-12);
}

TEST(SurfaceMesher, KeepsMaterialBoundariesAndCreasesSharpButWatertight) {
  // Another material on the right: its vertices are its own, yet the left face still takes the T-vertex.
  const SurfaceMesh s = mesh_faces(coarse_beside_fine(1), 1.0);
  EXPECT_EQ(test::count_t_junctions(s.mesh, 1e-9), 0u);
  EXPECT_GT(test::largest_colour_seam(s.mesh, 1e-9), 0.0);
  // A wall standing on the floor's edge (a crease): watertight, each side with its own normal.
  MeshFaces faces = coarse_beside_fine();
  faces.push_back(face({0, 0, 0}, {0, 0, 1}, {2, 0, 1}, {2, 0, 0}, 7.0, 2));
  const SurfaceMesh w = mesh_faces(faces, 1.0);
  EXPECT_EQ(test::count_t_junctions(w.mesh, 1e-9), 0u);
  for (size_t v = 0; v < w.mesh.vertex_count(); ++v)
    if (w.mesh.normals[3 * v + 1] > 0.5) {
      EXPECT_FLOAT_EQ(w.mesh.radiosity[3 * v], 7.0f);  // the wall's own value
    }
}

TEST(SurfaceMesher, IsDeterministic) {
  const SurfaceMesh a = mesh_faces(coarse_beside_fine(), 1.0), b = mesh_faces(coarse_beside_fine(), 1.0);
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.indices, b.mesh.indices);
  EXPECT_EQ(a.mesh.radiosity, b.mesh.radiosity);
}

}  // namespace
}  // namespace walkrad
