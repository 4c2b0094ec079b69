// Discontinuity meshing: the shadow boundaries' geometry against hand-computed lines, and the face cuts
// (area kept, convex pieces, a crack-free mesh with vertices on the boundary).
#include "walkrad/output/discontinuity_mesh.h"
#include "walkrad/output/shadow_boundaries.h"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "walkrad/testing/mesh_checks.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

// A 1 m square light 2 m above the floor, facing down; the floor 4 m square, facing up.
Polygon light() {
  Polygon p = test::quad({-0.5, 2, -0.5}, {0.5, 2, -0.5}, {0.5, 2, 0.5}, {-0.5, 2, 0.5});
  if (polygon_normal(p).y > 0) std::swap(p.v[1], p.v[3]);
  return p;
}
Polygon floor_quad() {
  Polygon p = test::quad({-2, 0, -2}, {2, 0, -2}, {2, 0, 2}, {-2, 0, 2});
  if (polygon_normal(p).y < 0) std::swap(p.v[1], p.v[3]);
  return p;
}

// Which of the lines x = c or z = c (c in lines) a segment lies on; -1: none.
int on_line(const BoundarySegment& g, const std::vector<double>& lines, bool& along_z) {
  for (size_t k = 0; k < lines.size(); ++k) {
    if (std::fabs(g.a.x - lines[k]) < 1e-9 && std::fabs(g.b.x - lines[k]) < 1e-9) { along_z = true; return int(k); }
    if (std::fabs(g.a.z - lines[k]) < 1e-9 && std::fabs(g.b.z - lines[k]) < 1e-9) { along_z = false; return int(k); }
  }
  return -1;
}

TEST(ShadowBoundaries, PanelHalfwayCastsItsPenumbraAndUmbraLines) {
  // A 0.2 m panel halfway up: by similar triangles (twice the height), corner e casts the panel's edge
  // at x = ±0.1 onto x = e + 2 (edge − e): the umbra's edges at ±0.3, the penumbra's outer edges at ±0.7;
  // each emitter edge's image through a panel corner (VE) falls on the same lines.
  const Polygon panel = test::quad({-0.1, 1, -0.1}, {0.1, 1, -0.1}, {0.1, 1, 0.1}, {-0.1, 1, 0.1});
  const std::vector<BoundarySegment> found = shadow_boundaries(light(), floor_quad(), {panel}, 1e-9);
  const std::vector<double> lines = {-0.7, -0.3, 0.3, 0.7};
  std::set<std::pair<int, bool>> hit;
  for (const BoundarySegment& g : found) {
    EXPECT_NEAR(g.a.y, 0, 1e-12);
    EXPECT_NEAR(g.b.y, 0, 1e-12);
    bool along_z = false;
    const int k = on_line(g, lines, along_z);
    EXPECT_GE(k, 0) << "(" << g.a.x << ", " << g.a.z << ")-(" << g.b.x << ", " << g.b.z << ")";
    if (k >= 0) hit.insert({k, along_z});
    // The emitter point whose visibility flips across the middle lies on the light's outline.
    EXPECT_NEAR(g.flips.y, 2, 1e-9);
    EXPECT_NEAR(std::max(std::fabs(g.flips.x), std::fabs(g.flips.z)), 0.5, 1e-9);
  }
  EXPECT_EQ(hit.size(), 8u);  // every line, both ways
}

TEST(ShadowBoundaries, ABoxKeepsOnlyWhatCrossesIt) {
  // The panel's lines clipped to the floor's quarter x, z in [0, 2]: the parts of x = 0.3 and 0.7 with
  // z ≥ 0 and of z = 0.3 and 0.7 with x ≥ 0, each a part of an unclipped segment on the same line,
  // and the flipping emitter point of each taken at its own middle (on the light's outline).
  const Polygon panel = test::quad({-0.1, 1, -0.1}, {0.1, 1, -0.1}, {0.1, 1, 0.1}, {-0.1, 1, 0.1});
  Bounds quarter;
  quarter.extend(Vec3{0, 0, 0});
  quarter.extend(Vec3{2, 0, 2});
  const std::vector<BoundarySegment> all = shadow_boundaries(light(), floor_quad(), {panel}, 1e-9);
  const std::vector<BoundarySegment> kept = shadow_boundaries(light(), floor_quad(), {panel}, 1e-9, &quarter);
  ASSERT_FALSE(kept.empty());
  EXPECT_LT(kept.size(), all.size());
  std::set<std::pair<int, bool>> hit;
  for (const BoundarySegment& g : kept) {
    for (const Vec3& x : {g.a, g.b}) {
      EXPECT_GE(x.x, -2e-9);  // the box is padded by tol
      EXPECT_GE(x.z, -2e-9);
    }
    bool along_z = false;
    const int k = on_line(g, {0.3, 0.7}, along_z);
    EXPECT_GE(k, 0) << "(" << g.a.x << ", " << g.a.z << ")-(" << g.b.x << ", " << g.b.z << ")";
    if (k >= 0) hit.insert({k, along_z});
    EXPECT_NEAR(g.flips.y, 2, 1e-9);
    EXPECT_NEAR(std::max(std::fabs(g.flips.x), std::fabs(g.flips.z)), 0.5, 1e-9);
    bool inside_one = false;  // a part of some unclipped segment
    for (const BoundarySegment& u : all) {
      const Vec3 d = u.b - u.a;
      auto on = [&](const Vec3& x) { return length(cross(x - u.a, d)) <= 1e-9 * length(d) && dot(x - u.a, d) >= -1e-9 && dot(x - u.b, d) <= 1e-9; };
      inside_one = inside_one || (on(g.a) && on(g.b));
    }
    EXPECT_TRUE(inside_one);
  }
  EXPECT_EQ(hit.size(), 4u);  // x = 0.3, 0.7 along z; z = 0.3, 0.7 along x
}

TEST(ShadowBoundaries, NothingFromAnOccluderOutsideTheLightsReach) {
  const Polygon above = test::quad({-0.1, 3, -0.1}, {0.1, 3, -0.1}, {0.1, 3, 0.1}, {-0.1, 3, 0.1});  // above the light
  const Polygon below = test::quad({-0.1, -1, -0.1}, {0.1, -1, -0.1}, {0.1, -1, 0.1}, {-0.1, -1, 0.1});  // under the floor
  const Polygon on_floor = test::quad({-0.1, 0, -0.1}, {0.1, 0, -0.1}, {0.1, 0, 0.1}, {-0.1, 0, 0.1});  // a rug
  EXPECT_TRUE(shadow_boundaries(light(), floor_quad(), {above, below, on_floor}, 1e-9).empty());
}

TEST(ShadowBoundaries, ACubeCastsOnlyItsSilhouette) {
  // A closed cube on the floor: edges between two faces that both face a light corner (or both turn
  // away) cast nothing; the same six faces given apart (no shared edges) cast every edge.
  Scene s;
  test::add_cube(s, {0.8, 0.25, 0.1}, 0.5);
  std::vector<BoundarySegment> closed = shadow_boundaries(light(), floor_quad(), s.polygons, 1e-9), apart;
  ASSERT_FALSE(closed.empty());
  for (const Polygon& p : s.polygons) {
    const std::vector<BoundarySegment> one = shadow_boundaries(light(), floor_quad(), {p}, 1e-9);
    apart.insert(apart.end(), one.begin(), one.end());
  }
  EXPECT_LT(closed.size(), apart.size());
  // The vertical edges stand on the floor: a silhouette's shadow starts at its foot.
  size_t from_feet = 0;
  for (const BoundarySegment& g : closed)
    for (const Vec3& p : {g.a, g.b})
      from_feet += std::fabs(std::fabs(p.x - 0.8) - 0.25) < 1e-9 && std::fabs(std::fabs(p.z - 0.1) - 0.25) < 1e-9;
  EXPECT_GT(from_feet, 0u);
}

MeshFace square(double x0, double z0, double s, uint32_t polygon) {
  MeshFace f;
  f.shape = test::quad({x0, 0, z0}, {x0, 0, z0 + s}, {x0 + s, 0, z0 + s}, {x0 + s, 0, z0});
  f.normal = polygon_normal(f.shape);
  f.radiosity = f.rho = Vec3(0.5, 0.5, 0.5);
  f.area = polygon_area(f.shape);
  f.polygon = polygon;
  return f;
}

TEST(CutFaces, PiecesKeepTheAreaAndTheMeshStaysCrackFree) {
  // A 4 × 4 grid of faces on one polygon, and a segment crossing three columns at a slant, ending in
  // the middle of a face.
  MeshFaces faces;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) faces.push_back(square(i, j, 1, 0));
  const BoundarySegment g{{0.2, 0, 0.5}, {2.5, 0, 2.9}, {}};
  const CutFaces cut = cut_faces(faces, {{g}}, 1e-9);
  ASSERT_GT(cut.faces.size(), faces.size());
  ASSERT_EQ(cut.from.size(), cut.faces.size());
  double before = 0, after = 0;
  for (const MeshFace& f : faces) before += f.area;
  for (size_t k = 0; k < cut.faces.size(); ++k) {
    after += cut.faces[k].area;
    EXPECT_NEAR(polygon_area(cut.faces[k].shape), cut.faces[k].area, 1e-12);
    EXPECT_GT(dot(polygon_normal(cut.faces[k].shape), faces[cut.from[k]].normal), 0.999);
  }
  EXPECT_NEAR(after, before, 1e-9);
  // Faces the segment does not pass through are whole (it stops at z = 2.9, short of the top row),
  // those it does are cut: (0, 0), (0, 1), (1, 1), (1, 2), (2, 2).
  size_t cut_count = 0;
  for (size_t f = 0; f < faces.size(); ++f) {
    cut_count += !cut.applied[f].empty();
    const double x0 = faces[f].shape.v[0].x, z0 = faces[f].shape.v[0].z;
    if (x0 >= 3 || z0 >= 3 || (x0 == 0 && z0 >= 2) || (x0 == 1 && z0 == 0)) {
      EXPECT_TRUE(cut.applied[f].empty()) << x0 << ", " << z0;
    }
  }
  EXPECT_EQ(cut_count, 5u);
  // The mesher anchors the points the cut leaves on uncut neighbours' edges: no T-junction.
  const SurfaceMesh mesh = mesh_faces(cut.faces, 1.0);
  EXPECT_EQ(test::count_t_junctions(mesh.mesh, 1e-9), 0u);
  // A vertex on the segment's line, inside its extent.
  bool on = false;
  for (size_t v = 0; v < mesh.mesh.vertex_count(); ++v) {
    const Vec3 p = test::vertex_position(mesh.mesh, v), d = g.b - g.a;
    const double t = dot(p - g.a, d) / dot(d, d);
    on = on || (t > 0.1 && t < 0.9 && length(g.a + d * t - p) < 1e-6);
  }
  EXPECT_TRUE(on);
}

TEST(CutFaces, ASliverIsNotCut) {
  const MeshFaces faces = {square(0, 0, 1, 0)};
  const BoundarySegment g{{1e-5, 0, -1}, {1e-5, 0, 2}, {}};  // 10 µm from the face's edge
  const CutFaces cut = cut_faces(faces, {{g}}, 1e-9);
  EXPECT_EQ(cut.faces.size(), 1u);
  EXPECT_TRUE(cut.applied[0].empty());
}

}  // namespace
}  // namespace walkrad
