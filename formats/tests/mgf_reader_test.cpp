// The MGF reader: every entity, transforms against hand-computed positions, includes, colours
// against hand computations, malformed input refused with file and line, and the classic scenes
// of ../shared/scenes/mgf (skipped where absent).
#include "walkrad/formats/mgf_reader.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "walkrad/formats/error.h"
#include "walkrad/formats/scene_reader.h"

namespace walkrad {
namespace {

namespace fs = std::filesystem;
const std::string kTestData = std::string(WALKRAD_SOURCE_DIR) + "/tests/data/mgf";
const std::string kSharedScenes = std::string(WALKRAD_SOURCE_DIR) + "/../shared/scenes/mgf";

// A fresh folder per test for the MGF files it writes.
std::string test_dir() {
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(testing::TempDir()) / ("mgf-" + std::string(info->name()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  const fs::path p = fs::path(dir) / name;
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
  return p.string();
}

Scene load(const std::string& text, MgfStats* stats = nullptr, const MgfOptions& options = {}) {
  return read_mgf(write(test_dir(), "scene.mgf", text), options, stats);
}

// A unit square in the plane z = 0 (counter-clockwise from +z) as vertices q0..q3, plus vertex a.
const std::string kSquare =
    "v q0 =\n p 0 0 0\nv q1 =\n p 1 0 0\nv q2 =\n p 1 1 0\nv q3 =\n p 0 1 0\nv a =\n p 1 0 0\n";

void expect_near(const Vec3& a, const Vec3& b, double tol = 1e-9) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

double total_area(const Scene& s) {
  double a = 0;
  for (const Polygon& p : s.polygons) a += polygon_area(p);
  return a;
}

bool has_warning(const Scene& s, const std::string& part) {
  for (const std::string& w : s.warnings)
    if (w.find(part) != std::string::npos) return true;
  return false;
}

// Every polygon is a planar convex triangle or quad.
void expect_valid_polygons(const Scene& s) {
  for (const Polygon& p : s.polygons) {
    ASSERT_TRUE(p.count == 3 || p.count == 4);
    const Vec3 n = polygon_normal(p);
    ASSERT_GT(length(n), 0.5);
    for (int k = 0; k < p.count; ++k) {
      ASSERT_TRUE(is_finite(p.v[k]));
      const Vec3 turn = cross(p.v[(k + 1) % p.count] - p.v[k], p.v[(k + 2) % p.count] - p.v[(k + 1) % p.count]);
      EXPECT_GE(dot(turn, n), -1e-12);
      EXPECT_NEAR(dot(p.v[k] - p.v[0], n), 0, 1e-9);
    }
  }
}

// ---- vertices and faces -------------------------------------------------------------------------

TEST(MgfReader, ReadsVerticesAndFacesWithTheirOrientation) {
  MgfStats stats;
  const Scene s = load(kSquare +
                           "m grey =\n c\n rd 0.5\n"
                           "f q0 q1 q2 q3\n"          // a quad, normal +z
                           "v t0 =\n p 0 0 1\n n 0 0 -1\n"
                           "v t1 = t0\n p 0 1 1\n"    // a copy of t0 (normal too), moved
                           "v t2 =\n p 1 0 1\n"
                           "f t0 t1 t2\n"             // a triangle, normal -z (clockwise from +z)
                           "v t2\n p 2 0 1\n"         // reselect t2 and move it: faces use the new place
                           "f t0 t1 t2\n",
                       &stats);
  ASSERT_EQ(s.polygons.size(), 3u);
  EXPECT_EQ(s.polygons[0].count, 4);
  expect_near(s.polygons[0].v[2], {1, 1, 0});
  expect_near(polygon_normal(s.polygons[0]), {0, 0, 1});
  EXPECT_EQ(s.polygons[1].count, 3);
  expect_near(polygon_normal(s.polygons[1]), {0, 0, -1});
  expect_near(s.polygons[2].v[2], {2, 0, 1});
  EXPECT_EQ(s.polygons[0].source, 14u);  // the line of the first f
  EXPECT_EQ(stats.faces, 3u);
  EXPECT_EQ(stats.entities.at("v"), 9u);
  EXPECT_EQ(stats.entities.at("n"), 1u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "grey");
}

TEST(MgfReader, SplitsConvexFacesIntoQuadsAndConcaveOnesIntoTriangles) {
  MgfStats stats;
  const Scene s = load(
      // A regular hexagon (convex): a fan of a quad and a quad.
      "v h0 =\n p 2 0 0\nv h1 =\n p 1 1.7320508075688772 0\nv h2 =\n p -1 1.7320508075688772 0\n"
      "v h3 =\n p -2 0 0\nv h4 =\n p -1 -1.7320508075688772 0\nv h5 =\n p 1 -1.7320508075688772 0\n"
      "f h0 h1 h2 h3 h4 h5\n"
      // An L (concave), area 3, at z = 5.
      "v l0 =\n p 0 0 5\nv l1 =\n p 2 0 5\nv l2 =\n p 2 1 5\nv l3 =\n p 1 1 5\nv l4 =\n p 1 2 5\nv l5 =\n p 0 2 5\n"
      "f l0 l1 l2 l3 l4 l5\n",
      &stats);
  expect_valid_polygons(s);
  double hexagon = 0, ell = 0;
  size_t hexagon_pieces = 0;
  for (const Polygon& p : s.polygons) {
    expect_near(polygon_normal(p), {0, 0, 1});
    if (p.v[0].z == 0) {
      hexagon += polygon_area(p);
      ++hexagon_pieces;
      EXPECT_EQ(p.count, 4);
    } else {
      ell += polygon_area(p);
      EXPECT_EQ(p.count, 3);
    }
  }
  EXPECT_EQ(hexagon_pieces, 2u);
  EXPECT_NEAR(hexagon, 6 * std::sqrt(3.0), 1e-9);
  EXPECT_NEAR(ell, 3, 1e-12);
  EXPECT_EQ(stats.faces, 2u);
}

TEST(MgfReader, TriangulatesSeamsAndHoles) {
  // A 4 × 4 wall with a 2 × 2 window: once as MGF's seam (the spec's "f" example), once with fh,
  // once with fh and the hole given the other way round, and once with two holes.
  const std::string corners =
      "v v1 =\n p 0 0 0\nv v2 =\n p 4 0 0\nv v3 =\n p 4 4 0\nv v4 =\n p 0 4 0\n"
      "v v5 =\n p 1 3 0\nv v6 =\n p 3 3 0\nv v7 =\n p 3 1 0\nv v8 =\n p 1 1 0\n"
      "v k1 =\n p 0.5 0.5 0\nv k2 =\n p 1.5 0.5 0\nv k3 =\n p 1.5 1.5 0\nv k4 =\n p 0.5 1.5 0\n"
      "v k5 =\n p 2.5 2.5 0\nv k6 =\n p 3.5 2.5 0\nv k7 =\n p 3.5 3.5 0\nv k8 =\n p 2.5 3.5 0\n";
  for (const std::string face : {"f v1 v2 v3 v4 v5 v6 v7 v8 v5 v4", "fh v1 v2 v3 v4 - v5 v6 v7 v8",
                                 "fh v1 v2 v3 v4 - v8 v7 v6 v5"}) {
    SCOPED_TRACE(face);
    const Scene s = load(corners + face + "\n");
    expect_valid_polygons(s);
    EXPECT_NEAR(total_area(s), 16 - 4, 1e-9);
    for (const Polygon& p : s.polygons) {
      expect_near(polygon_normal(p), {0, 0, 1});
      const Vec3 c = polygon_centroid(p);
      EXPECT_FALSE(c.x > 1 && c.x < 3 && c.y > 1 && c.y < 3) << "a piece covers the window";
    }
  }
  const Scene two = load(corners + "fh v1 v2 v3 v4 - k1 k2 k3 k4 - k5 k6 k7 k8\n");
  expect_valid_polygons(two);
  EXPECT_NEAR(total_area(two), 16 - 2, 1e-9);

  // A concave comb (teeth along y) in a tilted plane with 12 holes: triangles (either
  // orientation) and diamonds in a grid, several sharing the rightmost x with another.
  std::ostringstream text;
  const std::vector<std::pair<double, double>> comb = {{0, 0}, {10, 0}, {10, 6}, {9, 6}, {9, 3}, {7, 3}, {7, 6},
                                                       {5, 6}, {5, 3}, {3, 3}, {3, 6}, {0, 6}};
  auto put = [&](const std::string& name, double x, double y) {
    text << "v " << name << " =\n p " << x << " " << y << " " << 0.5 * x + 0.25 * y << "\n";
  };
  std::string face = "fh";
  for (size_t i = 0; i < comb.size(); ++i) {
    put("c" + std::to_string(i), comb[i].first, comb[i].second);
    face += " c" + std::to_string(i);
  }
  double holes = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 2; ++j) {
      const double x = 0.8 + 1.5 * i, y = 0.6 + 1.2 * j;
      const std::string h = "h" + std::to_string(i) + "_" + std::to_string(j) + "_";
      face += " -";
      if ((i + j) % 2) {  // a diamond, area 0.5 × 0.8 / 2 × 2
        put(h + "0", x, y - 0.4); put(h + "1", x + 0.25, y); put(h + "2", x, y + 0.4); put(h + "3", x - 0.25, y);
        face += " " + h + "0 " + h + "1 " + h + "2 " + h + "3";
        holes += 0.2;
      } else {  // a right triangle, area 0.18, clockwise or counter-clockwise
        put(h + "0", x, y); put(h + "1", x + 0.6, y); put(h + "2", x, y + 0.6);
        face += i % 2 ? " " + h + "0 " + h + "1 " + h + "2" : " " + h + "2 " + h + "1 " + h + "0";
        holes += 0.18;
      }
    }
  const Scene comb_scene = load(text.str() + face + "\n");
  expect_valid_polygons(comb_scene);
  const double stretch = std::sqrt(1 + 0.25 + 0.0625);  // area scale of the tilted plane
  EXPECT_NEAR(total_area(comb_scene), (10 * 6 - 2 * 2 * 3 - holes) * stretch, 1e-9);  // two 2 × 3 notches
  EXPECT_FALSE(has_warning(comb_scene, "self-intersecting"));
}

TEST(MgfReader, SplitsNonPlanarFacesAndDropsFacesWithoutArea) {
  const Scene s = load(kSquare +
                       "v up =\n p 1 1 0.5\n"
                       "f q0 q1 up q3\n"     // not planar: two triangles
                       "f q0 q1 a\n");        // q1 and a coincide: no area
  ASSERT_EQ(s.polygons.size(), 2u);
  EXPECT_EQ(s.polygons[0].count, 3);
  EXPECT_EQ(s.dropped_degenerate, 1u);
  EXPECT_TRUE(has_warning(s, "1 non-planar faces split into triangles"));
  EXPECT_TRUE(has_warning(s, "1 faces without area dropped"));
}

TEST(MgfReader, JoinsContinuationLines) {
  const Scene s = load(kSquare + "f q0 \\\n  q1 q2 \\\n q3\n");
  ASSERT_EQ(s.polygons.size(), 1u);
  EXPECT_EQ(s.polygons[0].count, 4);
}

// ---- curved primitives --------------------------------------------------------------------------

// Faces of a closed or open surface about `centre`: each points away from it (or towards it).
void expect_facing(const Scene& s, const std::function<Vec3(const Vec3&)>& outward, bool out = true) {
  for (const Polygon& p : s.polygons) {
    const double d = dot(polygon_normal(p), normalize(outward(polygon_centroid(p))));
    if (out) EXPECT_GT(d, 0.5);
    else EXPECT_LT(d, -0.5);
  }
}

TEST(MgfReader, TessellatesSpheresToTheTolerance) {
  MgfStats stats;
  const Scene s = load("v c =\n p 1 2 3\nsph c 2\n", &stats);
  // 4 segments per quarter circle (tolerance 0.02): 8 bands of 16, poles as triangles.
  EXPECT_EQ(s.polygons.size(), 128u);
  EXPECT_EQ(stats.primitives, 1u);
  expect_valid_polygons(s);
  const Vec3 c{1, 2, 3};
  expect_facing(s, [&](const Vec3& p) { return p - c; });
  for (const Polygon& p : s.polygons)
    for (int k = 0; k < p.count; ++k) {
      EXPECT_NEAR(length(p.v[k] - c), 2, 1e-12);  // vertices on the sphere
      const Vec3 mid = (p.v[k] + p.v[(k + 1) % p.count]) * 0.5;
      EXPECT_GE(length(mid - c), 2 * (1 - 0.02));  // chords within the tolerance
    }
  EXPECT_NEAR(total_area(s), 4 * kPi * 4, 4 * kPi * 4 * 0.04);
  // Inward for a negative radius; a finer tolerance: 8 segments per quarter circle.
  const Scene in = load("v c =\n p 1 2 3\nsph c -2\n", nullptr, MgfOptions{0.005, 1, 50'000'000});
  EXPECT_EQ(in.polygons.size(), 512u);
  expect_facing(in, [&](const Vec3& p) { return p - c; }, false);
}

TEST(MgfReader, TessellatesCylindersConesRingsTorusesAndPrisms) {
  const std::string axis = "v a =\n p 0 0 0\nv b =\n p 0 0 2\n";
  auto radial = [](const Vec3& p) { return Vec3{p.x, p.y, 0}; };
  {
    const Scene s = load(axis + "cyl a 0.5 b\n");
    EXPECT_EQ(s.polygons.size(), 16u);
    expect_valid_polygons(s);
    expect_facing(s, radial);
    for (const Polygon& p : s.polygons) {
      EXPECT_EQ(p.count, 4);
      EXPECT_GE(length(radial(polygon_centroid(p))), 0.5 * (1 - 0.02));
    }
    EXPECT_NEAR(total_area(s), 2 * kPi * 0.5 * 2, 2 * kPi * 0.5 * 2 * 0.02);
  }
  {
    const Scene s = load(axis + "cone a -1 b 0\n");  // inward, apex at b: triangles
    EXPECT_EQ(s.polygons.size(), 16u);
    for (const Polygon& p : s.polygons) EXPECT_EQ(p.count, 3);
    expect_facing(s, radial, false);
  }
  {
    const Scene s = load(axis + "v r =\n p 0 0 1\n n 0 1 0\nring r 0 1\nring r 2 3\n");
    EXPECT_EQ(s.polygons.size(), 32u);
    for (const Polygon& p : s.polygons) expect_near(polygon_normal(p), {0, 1, 0});
    EXPECT_NEAR(total_area(s), kPi * (1 + 9 - 4), kPi * 10 * 0.04);
  }
  {
    const Scene s = load("v t =\n p 0 0 0\n n 0 0 1\ntorus t 1 3\n");
    EXPECT_EQ(s.polygons.size(), 256u);
    expect_valid_polygons(s);
    // Outwards from the tube's centre circle (radius 2 about the z axis).
    expect_facing(s, [](const Vec3& p) { return p - normalize(Vec3{p.x, p.y, 0}) * 2; });
    EXPECT_NEAR(total_area(s), 4 * kPi * kPi * 2 * 1, 4 * kPi * kPi * 2 * 0.04);
  }
  {
    MgfStats stats;
    const Scene s = load(kSquare + "prism q0 q1 q2 q3 0.5\n", &stats);  // a box below the square
    ASSERT_EQ(s.polygons.size(), 6u);
    const Vec3 centre{0.5, 0.5, -0.25};
    expect_facing(s, [&](const Vec3& p) { return p - centre; });
    Vec3 sum;
    for (const Polygon& p : s.polygons) sum += polygon_area_normal(p);
    expect_near(sum, {0, 0, 0}, 1e-12);  // closed
    EXPECT_NEAR(total_area(s), 2 + 4 * 0.5, 1e-12);
    EXPECT_EQ(stats.entities.at("prism"), 1u);
  }
}

// ---- transforms ---------------------------------------------------------------------------------

Vec3 first_vertex(const std::string& text) {
  const Scene s = load(kSquare + text);
  return s.polygons.at(0).v[1];  // q1 = (1, 0, 0) before the transform
}

TEST(MgfReader, ComposesTransformsInTheOrderGiven) {
  // Each argument acts on the geometry as moved by the ones before it.
  expect_near(first_vertex("xf -t 1 0 0 -rz 90\nf q0 q1 q2 q3\nxf\n"), {0, 2, 0});   // (2,0,0) turned
  expect_near(first_vertex("xf -rz 90 -t 1 0 0\nf q0 q1 q2 q3\nxf\n"), {1, 1, 0});   // (0,1,0) moved
  expect_near(first_vertex("xf -rx 90\nf q0 q1 q2 q3\nxf\n"), {1, 0, 0});
  expect_near(first_vertex("xf -ry 90\nf q0 q1 q2 q3\nxf\n"), {0, 0, -1});          // x → -z
  expect_near(first_vertex("xf -ry 30 -s 2\nf q0 q1 q2 q3\nxf\n"),
              {2 * std::cos(kPi / 6), 0, -2 * std::sin(kPi / 6)}, 1e-12);
  // Rotating about a point: -t to the origin, turn, -t back (the MGF spec's example): q0 at
  // (0,0,0) turns 90° about (1,1,0) and lands on (2,0,0).
  {
    const Scene s = load(kSquare + "xf -t -1 -1 0 -rz 90 -t 1 1 0\nf q0 q1 q2 q3\nxf\n");
    expect_near(s.polygons[0].v[0], {2, 0, 0});
  }
  // Nested: the inner transform first, then the outer.
  expect_near(first_vertex("xf -t 0 0 5\nxf -s 2\nf q0 q1 q2 q3\nxf\nxf\n"), {2, 0, 5});
  expect_near(first_vertex("xf -s 2\nxf -t 0 0 5\nf q0 q1 q2 q3\nxf\nxf\n"), {2, 0, 10});
  // -i repeats the arguments after it.
  expect_near(first_vertex("xf -rz 90 -i 3 -t 1 0 0\nf q0 q1 q2 q3\nxf\n"), {3, 1, 0});
  expect_near(first_vertex("xf -i 1000000 -t 0.000001 0 0\nf q0 q1 q2 q3\nxf\n"), {2, 0, 0}, 1e-9);
  // A transform acts where a vertex is used, not where it is defined; after xf ends, none.
  {
    const Scene s = load("xf -t 0 0 7\nv late =\n p 5 5 5\nxf\n" + kSquare + "f late q1 q2\n");
    expect_near(s.polygons[0].v[0], {5, 5, 5});
  }
}

TEST(MgfReader, MirrorsKeepTheFrontSide) {
  for (const std::string m : {"-mx", "-my", "-mz", "-s -1"}) {
    SCOPED_TRACE(m);
    const Scene s = load(kSquare + "v z =\n p 0 0 1\nxf " + m + "\nf q0 q1 z\nxf\n");
    // The triangle's front (its right-hand-rule normal is -y before the mirror) is mirrored with
    // it: the front is the mirror image of the -y side, not the right-hand rule of the image.
    const Vec3 expected = m == "-my" || m == "-s -1" ? Vec3{0, 1, 0} : Vec3{0, -1, 0};
    expect_near(polygon_normal(s.polygons.at(0)), expected);
  }
  // A mirrored sphere still faces out.
  const Scene ball = load("v c =\n p 1 0 0\nxf -mx -t 5 0 0\nsph c 1\nxf\n");
  expect_facing(ball, [](const Vec3& p) { return p - Vec3{4, 0, 0}; });
}

TEST(MgfReader, RepeatsArrays) {
  MgfStats stats;
  const Scene s = load(kSquare + "xf -t 0 0 1 -a 3 -t 2 0 0\nf q0 q1 q2 q3\nxf\n"
                                 "xf -a 2 -t 10 0 0 -a 3 -t 0 10 0\nf q0 q1 q2 q3\nxf\n",
                       &stats);
  ASSERT_EQ(s.polygons.size(), 9u);
  for (int k = 0; k < 3; ++k) expect_near(s.polygons[k].v[0], {2.0 * k, 0, 1});
  // Two arrays: the last one changes fastest.
  const Vec3 grid[6] = {{0, 0, 0}, {0, 10, 0}, {0, 20, 0}, {10, 0, 0}, {10, 10, 0}, {10, 20, 0}};
  for (int k = 0; k < 6; ++k) expect_near(s.polygons[3 + k].v[0], grid[k]);
  EXPECT_EQ(stats.faces, 9u);
  EXPECT_EQ(stats.entities.at("f"), 9u);
}

// ---- includes -----------------------------------------------------------------------------------

TEST(MgfReader, IncludesFilesRelativeToTheIncludingFileWithTransforms) {
  const std::string dir = test_dir();
  write(dir, "parts/panel.mgf", "i sub/corners.mgf\nf p0 p1 p2 p3\n");  // relative to parts/
  write(dir, "parts/sub/corners.mgf", "v p0 =\n p 0 0 0\nv p1 =\n p 1 0 0\nv p2 =\n p 1 1 0\nv p3 =\n p 0 1 0\n");
  const std::string main = write(dir, "main.mgf",
                                 "xf -t 0 0 3\n"
                                 "i parts/panel.mgf -rz 90 -t 5 0 0 -a 2 -t 0 2 0\n"
                                 "xf\n");
  MgfStats stats;
  const Scene s = read_mgf(main, {}, &stats);
  ASSERT_EQ(s.polygons.size(), 2u);
  // p1 = (1,0,0): turned to (0,1,0), moved to (5,1,0), instance k moved by (0,2k,0), then the outer +3 z.
  expect_near(s.polygons[0].v[1], {5, 1, 3});
  expect_near(s.polygons[1].v[1], {5, 3, 3});
  EXPECT_EQ(stats.files, 5u);  // main, then panel and corners twice
}

TEST(MgfReader, ReadsTheTestRoom) {
  MgfStats stats;
  const Scene s = read_scene(kTestData + "/room.mgf");
  const Scene again = read_mgf(kTestData + "/room.mgf", {}, &stats);
  EXPECT_EQ(s.polygons.size(), again.polygons.size());
  expect_valid_polygons(s);
  EXPECT_EQ(stats.faces, 8u);  // 6 room faces + the lamp panel in a 2-instance include array
  EXPECT_EQ(stats.emitting_faces, 2u);
  EXPECT_EQ(stats.primitives, 7u);  // prism, sph, cyl, ring, torus + a cone per lamp
  EXPECT_EQ(stats.files, 4u);  // room, materials, the lamp twice
  size_t emitters = 0;
  for (const Polygon& p : s.polygons) {
    if (!s.materials[p.material].emits()) continue;
    ++emitters;
    expect_near(polygon_normal(p), {0, 0, -1});
    EXPECT_NEAR(polygon_centroid(p).z, 2.49, 1e-12);
    EXPECT_NEAR(polygon_area(p), 0.16, 1e-12);
  }
  EXPECT_EQ(emitters, 2u);
  const Bounds b = s.bounds();
  expect_near(b.lo, {0, 0, 0});
  expect_near(b.hi, {4, 3, 2.5});
  // The wall with the window: 3 × 2.5 less 1 × 1.
  double window_wall = 0;
  for (const Polygon& p : s.polygons)
    if (std::fabs(polygon_centroid(p).x - 4) < 1e-12 && polygon_normal(p).x < -0.99) window_wall += polygon_area(p);
  EXPECT_NEAR(window_wall, 7.5 - 1, 1e-9);
}

// ---- materials and colours ----------------------------------------------------------------------

Material material_of(const std::string& definition) {
  const Scene s = load(kSquare + definition + "\nf q0 q1 q2 q3\n");
  return s.materials.at(s.polygons.at(0).material);
}

TEST(MgfReader, GreyReflectanceAndEmission) {
  // A grey by chromaticity: cxy 0.333 0.333 with rd 0.5 gives 0.5 in every channel.
  const Material grey = material_of("m g =\n c\n  cxy 0.333 0.333\n rd 0.5");
  expect_near(grey.reflectance, {0.5, 0.5, 0.5}, 1e-3);
  // ed in lm/m² / 179 lm/W = W/m² of emitted radiosity.
  const Material lamp = material_of("m l =\n c\n ed 358");
  expect_near(lamp.emission, {2, 2, 2}, 1e-12);
  EXPECT_TRUE(lamp.emits());
  expect_near(lamp.reflectance, {0, 0, 0});
  // The unnamed default material: black, not emitting.
  const Material none = material_of("");
  EXPECT_EQ(none.name, "unnamed");
  expect_near(none.reflectance, {0, 0, 0});
  EXPECT_FALSE(none.emits());
}

TEST(MgfReader, SaturatedColoursAgainstHandComputations) {
  // The chromaticity that sRGB's pure red has when MGF's neutral (E) is mapped to D65 by scaling
  // X and Z: red's XYZ (0.4124, 0.2126, 0.0193) with X / 0.95046 and Z / 1.08906 is
  // (0.43390, 0.2126, 0.01772), x = 0.6532, y = 0.3201. With rd = 0.2126 / 2 it is (0.5, 0, 0).
  const Material red = material_of("m r =\n c\n  cxy 0.6532 0.3201\n rd 0.1063");
  expect_near(red.reflectance, {0.5, 0, 0}, 3e-3);
  // An in-gamut colour keeps its luminance (Rec. 709) = rd, exactly up to the coefficients' digits.
  const Material green = material_of("m g =\n c\n  cxy 0.3 0.45\n rd 0.4");
  EXPECT_NEAR(luminance(green.reflectance), 0.4, 1e-4);
  EXPECT_GT(green.reflectance.y, green.reflectance.x);
  EXPECT_GT(green.reflectance.y, green.reflectance.z);
  // Outside the gamut (outside the spectral locus even, from corridor.mgf): desaturated towards
  // the grey of the same luminance, no negative channel, and a warning.
  const Scene s = load(kSquare + "m r =\n c\n  cxy 0.75 0.1\n rd 0.1\nf q0 q1 q2 q3\n");
  const Vec3 rho = s.materials.at(0).reflectance;
  EXPECT_GE(std::min({rho.x, rho.y, rho.z}), 0.0);
  EXPECT_NEAR(luminance(rho), 0.1, 1e-4);
  EXPECT_GT(rho.x, rho.y);
  EXPECT_TRUE(has_warning(s, "outside the sRGB gamut"));
}

TEST(MgfReader, SpectraBlackBodiesAndMixtures) {
  // A flat spectrum is MGF's neutral.
  expect_near(material_of("m w =\n c\n  cspec 380 780 1 1 1 1\n rd 0.5").reflectance, {0.5, 0.5, 0.5}, 1e-3);
  // A black body at 2856 K is CIE illuminant A, chromaticity (0.44757, 0.40745) (CIE 015).
  const Vec3 a = material_of("m a =\n c\n  cct 2856\n rd 0.5").reflectance;
  const Vec3 a_xy = material_of("m a =\n c\n  cxy 0.44757 0.40745\n rd 0.5").reflectance;
  expect_near(a, a_xy, 2e-3);
  EXPECT_GT(a.x, a.z);
  // A narrow band at 550 nm is green.
  const Vec3 g = material_of("m g =\n c\n  cspec 540 560 0 1 0\n rd 0.3").reflectance;
  EXPECT_GT(g.y, 2 * g.x);
  // cmix weighs chromaticities by luminance: 1 part (0.64, 0.33) and 1 part (0.30, 0.60) have XYZ
  // per unit luminance (1.93939, 1, 0.09091) and (0.5, 1, 0.16667); the sum (2.43939, 2, 0.25758)
  // has x = 2.43939 / 4.69697 = 0.51935, y = 2 / 4.69697 = 0.42581.
  const Vec3 mix = material_of("c r =\n cxy 0.64 0.33\nc g =\n cxy 0.30 0.60\n"
                               "m m =\n c\n  cmix 1 r 1 g\n rd 0.4").reflectance;
  const Vec3 by_hand = material_of("m m =\n c\n  cxy 0.51935 0.42581\n rd 0.4").reflectance;
  expect_near(mix, by_hand, 2e-4);
  // A chromaticity with y = 0 (hospital/blokken2.mgf) has no luminance: black, with a warning.
  const Scene s = load(kSquare + "c purple =\n cxy 0.4 0\nm p =\n c purple\n rd 0.2\n ed 100\nf q0 q1 q2 q3\n");
  EXPECT_FALSE(s.materials.at(0).emits());
  EXPECT_TRUE(has_warning(s, "no luminance"));
}

TEST(MgfReader, MaterialsTemplatesRedefinitionsAndSides) {
  MgfStats stats;
  const Scene s = load(kSquare +
                           "m one =\n c\n rd 0.2\n sides 1\nf q0 q1 q2 q3\n"
                           "m two = one\n sides 2\nf q0 q1 q2 q3\n"       // a copy, two-sided
                           "m one\n rd 0.4\nf q0 q1 q2 q3\n"              // changed: a second scene material
                           "m plain =\n rd 0.3\n rs 0.1 0.05\n ts 0.1 0\n td 0.1\n ir 1.5 0\nf q0 q1 q2 q3\n",
                       &stats);
  ASSERT_EQ(s.polygons.size(), 5u);
  ASSERT_EQ(s.materials.size(), 4u);
  EXPECT_EQ(s.materials[0].name, "one");
  EXPECT_EQ(s.materials[1].name, "two");
  EXPECT_EQ(s.materials[2].name, "one#2");
  EXPECT_NEAR(s.materials[2].reflectance.x, 0.4, 1e-12);
  // The two-sided face: the same quad twice, the second reversed.
  EXPECT_EQ(s.polygons[1].material, 1u);
  EXPECT_EQ(s.polygons[2].material, 1u);
  expect_near(polygon_normal(s.polygons[1]), {0, 0, 1});
  expect_near(polygon_normal(s.polygons[2]), {0, 0, -1});
  EXPECT_EQ(stats.back_polygons, 1u);
  EXPECT_TRUE(has_warning(s, "specular reflectance (rs) ignored in 1 materials (plain)"));
  // ts with roughness 0: clear glass, of the ir index.
  EXPECT_TRUE(s.materials[3].is_clear_glass());
  EXPECT_NEAR(luminance(s.materials[3].clear), 0.1, 1e-3);
  EXPECT_NEAR(s.materials[3].ior, 1.5, 1e-12);
  EXPECT_FALSE(has_warning(s, "specular transmittance"));
  EXPECT_NEAR(s.materials[3].transmittance.x, 0.1, 1e-3);  // td: diffuse transmission (read, not ignored)
  EXPECT_FALSE(has_warning(s, "diffuse transmittance (td) ignored"));
  EXPECT_TRUE(has_warning(s, "1 materials do not state 'sides'"));
  // MGF's own default (two-sided) on request.
  const Scene both = load(kSquare + "m p =\n rd 0.5\nf q0 q1 q2 q3\n", nullptr, MgfOptions{0.02, 2, 50'000'000});
  EXPECT_EQ(both.polygons.size(), 2u);
  // Reflectance just below 1 is capped at 0.99; 1 itself is kept, with a warning (the bake refuses a
  // closed scene where nothing absorbs).
  const Scene white = load(kSquare + "m w =\n rd 0.995\nf q0 q1 q2 q3\n");
  expect_near(white.materials[0].reflectance, {0.99, 0.99, 0.99});
  EXPECT_TRUE(has_warning(white, "capped at 0.99"));
  const Scene one = load(kSquare + "m w =\n rd 1\nf q0 q1 q2 q3\n");
  EXPECT_LE(max_component(one.materials[0].reflectance), 1.0);
  EXPECT_NEAR(luminance(one.materials[0].reflectance), 1.0, 1e-6);
  EXPECT_TRUE(has_warning(one, "rd 1 in 1 materials (w): they absorb nothing"));
  EXPECT_FALSE(has_warning(one, "capped"));
}

TEST(MgfReader, ObjectsAndUnknownEntities) {
  MgfStats stats;
  const Scene s = load(kSquare + "o room\n o wall\n  f q0 q1 q2 q3\n o\n" +
                           std::string(12 * 1, ' ') + "foo 1 2 3\nfoo\nfoo\nfoo\nfoo\nfoo\nfoo\nfoo\nfoo\nfoo\nfoo\nfoo\n"
                           "bar baz\n#comment\n# another\n",
                       &stats);
  EXPECT_EQ(s.polygons.size(), 1u);
  EXPECT_EQ(stats.entities.at("o"), 3u);
  EXPECT_TRUE(has_warning(s, "12 unknown 'foo' entities skipped (first at "));
  EXPECT_TRUE(has_warning(s, "1 unknown 'bar' entity skipped"));
  EXPECT_TRUE(has_warning(s, "1 objects (o) left open"));
}

// ies: a luminaire per array instance at its transform's origin, aimed along the
// transform's −Z with its +Y as the profile's 90° plane; candela × multiplier ÷ 179 lm/W per channel
// in the current colour; the profile read once and shared; a missing or bad profile names its file.
TEST(MgfReader, IesLuminaires) {
  const std::string dir = test_dir();
  write(dir, "lamps/spot.ies",
        "IESNA:LM-63-2002\r\nTILT=NONE\r\n1 -1 1 3 1 1 2 0 0 0\r\n1 1 10\r\n0 45 90\r\n0\r\n100 50 0\r\n");
  const std::string scene = write(dir, "scene.mgf", kSquare + "m w =\n rd 0.5\nf q0 q1 q2 q3\n"
                                                  "ies lamps/spot.ies -m 2 -rz 90 -t 1 2 3 -a 2 -t 0 0.5 0\n");
  const Scene s = read_mgf(scene);
  ASSERT_EQ(s.lights.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    const PunctualLight& l = s.lights[k];
    EXPECT_EQ(l.type, PunctualLight::Type::ies);
    expect_near(l.position, {1, 2 + 0.5 * double(k), 3});
    expect_near(l.direction, {0, 0, -1});
    expect_near(l.up, {-1, 0, 0});  // +Y turned 90° about z
    expect_near(l.intensity, {2 / 179.0, 2 / 179.0, 2 / 179.0}, 1e-12);
    ASSERT_TRUE(l.profile);
    EXPECT_EQ(l.profile.get(), s.lights[0].profile.get());
    EXPECT_NEAR(l.profile->intensity({0, 0, -1}), 100, 1e-9);
    EXPECT_NE(l.profile->text.find("TILT=NONE"), std::string::npos);
  }
  const std::string missing = write(dir, "missing.mgf", kSquare + "m w =\n rd 0.5\nf q0 q1 q2 q3\nies nowhere.ies\n");
  try {
    read_mgf(missing);
    ADD_FAILURE() << "a missing profile was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere.ies"), std::string::npos) << e.what();
  }
  write(dir, "bad.ies", "IESNA:LM-63-2002\r\nTILT=NONE\r\n1 -1 1 3 1 1 2 0 0 0\r\n1 1 10\r\n0 45 90\r\n0\r\n100 -50 0\r\n");
  const std::string bad = write(dir, "bad.mgf", kSquare + "m w =\n rd 0.5\nf q0 q1 q2 q3\nies bad.ies -m 2\n");
  try {
    read_mgf(bad);
    ADD_FAILURE() << "a negative candela was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.file().find("bad.ies"), std::string::npos) << e.what();
    EXPECT_EQ(e.place(), "line 7") << e.what();
  }
}

// ---- malformed input ----------------------------------------------------------------------------

struct Bad {
  std::string text;  // the entity (or entities: the last one is the bad one), after a 15-line head
  std::string part;  // expected in the message
  ExitCode code = kExitBadInput;
};

TEST(MgfReader, RefusesMalformedEntitiesWithFileAndLine) {
  const std::string head = kSquare + "v r =\n p 0 0 1\n n 0 0 1\nc red =\n cxy 0.6 0.3\n";
  const int head_lines = 15;
  const Bad cases[] = {
      {"v 1abc =", "not a name"},
      {"v x = nothere", "undefined vertex 'nothere'"},
      {"v x y", "expected '='"},
      {"v nothere", "undefined vertex 'nothere'"},
      {"v a b c d e", "expected 0 to 3 arguments, got 5"},
      {"p 1 2", "p: expected 3 arguments, got 2"},
      {"p 1 2 x", "'x' is not a number"},
      {"n 1 2 nan", "'nan' is not a number"},
      {"f q0 q1", "f: expected at least 3 arguments, got 2"},
      {"f q0 q1 nothere", "undefined vertex 'nothere'"},
      {"fh q0 q1 q2 q3 - q0 q1", "at least 3 vertices"},
      {"v o0 =\n p 5 5 0\nv o1 =\n p 6 5 0\nv o2 =\n p 6 6 0\nfh q0 q1 q2 q3 - o0 o1 o2", "not inside the outline"},
      {"c nothere", "undefined colour 'nothere'"},
      {"c a = b c d", "expected 0 to 3 arguments, got 5"},
      {"cxy 0.8 0.5", "x + y <= 1"},
      {"cxy 0.3", "cxy: expected 2 arguments, got 1"},
      {"cspec 700 400 1 1", "must increase"},
      {"cspec 400 700 1", "at least 4 arguments, got 3"},
      {"cspec 400 700 0 0", "no positive sum"},
      {"cct 500", "[1000, 100000] K"},
      {"cmix 1 red", "at least 4 arguments"},
      {"cmix 1 red 1 nothere", "undefined colour 'nothere'"},
      {"cmix 1 red -1 red", "negative weight"},
      {"m nothere", "undefined material 'nothere'"},
      {"sides 3", "expected 1 or 2"},
      {"rd 1.5", "must lie in [0, 1]"},
      {"rd", "rd: expected 1 argument, got 0"},
      {"td -0.1", "must lie in [0, 1]"},
      {"ed -1", "must not be negative"},
      {"rs 0.5", "rs: expected 2 arguments, got 1"},
      {"ts 0.5 -1", "roughness must not be negative"},
      {"ir 0 0", "index of refraction"},
      {"sph q0 0", "radius must not be 0"},
      {"sph nothere 1", "undefined vertex 'nothere'"},
      {"cyl q0 1 q0", "coincide"},
      {"cone q0 1 q2 -1", "opposite signs"},
      {"cone q0 0 q2 0", "both be 0"},
      {"ring q0 0 1", "needs a normal"},
      {"ring r 2 1", "0 <= rmin < rmax"},
      {"torus r 2 1", "0 <= rmin < rmax"},
      {"prism q0 q1 q2 0", "length must not be 0"},
      {"prism q0 q1 1", "at least 4 arguments"},
      {"prism q0 q1 a 1", "base has no area"},
      {"xf -q", "unknown transform argument '-q'"},
      {"xf -t 1 2", "'-t' needs 3 values"},
      {"xf -rz x", "'x' is not a number"},
      {"xf -s 0", "collapses"},
      {"xf", "not begun in this file"},
      {"xf -a 0", "the count must lie in [1, 1000000]"},
      {"xf -a 1001 -a 1000", "more than 1000000 instances", kExitLimitReached},
      {"xf -a 1000000 -a 1000000 -a 1000000 -a 1000000", "more than 1000000 instances", kExitLimitReached},
      {"xf -a 1000\nxf -a 1001", "more than 1000000 instances", kExitLimitReached},
      {"i", "i: expected at least 1 argument, got 0"},
      {"i nothere.mgf", "cannot open included file"},
      {"o", "end of an object that was not begun"},
      {"o a b", "o: expected 0 to 1 arguments, got 2"},
  };
  for (const Bad& c : cases) {
    SCOPED_TRACE(c.text);
    const std::string text = head + c.text + "\n";
    const int line = head_lines + 1 + int(std::count(c.text.begin(), c.text.end(), '\n'));
    const std::string path = write(test_dir(), "bad.mgf", text);
    try {
      read_mgf(path);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_EQ(e.place(), "line " + std::to_string(line));
      EXPECT_NE(e.message().find(c.part), std::string::npos) << e.what();
      EXPECT_EQ(e.code(), c.code);
    }
  }
}

TEST(MgfReader, RefusesIncludeCyclesAndDeepIncludes) {
  const std::string dir = test_dir();
  const std::string a = write(dir, "a.mgf", "# a\ni sub/b.mgf\n");
  const std::string b = write(dir, "sub/b.mgf", "\n\ni ../a.mgf\n");
  try {
    read_mgf(a);
    ADD_FAILURE() << "accepted a cycle";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), b);  // the file that closes the cycle, at its include
    EXPECT_EQ(e.place(), "line 3");
    EXPECT_NE(e.message().find("include cycle: a.mgf → b.mgf → a.mgf"), std::string::npos) << e.what();
  }
  // 40 files each including the next.
  for (int k = 0; k < 40; ++k) write(dir, "deep" + std::to_string(k) + ".mgf", "i deep" + std::to_string(k + 1) + ".mgf\n");
  write(dir, "deep40.mgf", kSquare + "f q0 q1 q2\n");
  try {
    read_mgf(dir + "/deep0.mgf");
    ADD_FAILURE() << "accepted 40 nested includes";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("deeper than 32"), std::string::npos) << e.what();
    EXPECT_EQ(e.code(), kExitLimitReached);
  }
  // A missing scene file, an empty scene and too many polygons.
  EXPECT_THROW(read_mgf(dir + "/nothere.mgf"), InputError);
  EXPECT_THROW(load("# nothing\n"), InputError);
  try {
    load("v c =\n p 0 0 0\nsph c 1\n", nullptr, MgfOptions{0.02, 1, 100});
    ADD_FAILURE() << "accepted more polygons than the limit";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), kExitLimitReached);
  }
  std::string huge = "f";
  for (int k = 0; k < 4097; ++k) huge += " q0";
  try {
    load(kSquare + huge + "\n");
    ADD_FAILURE() << "accepted a face of 4097 vertices";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), kExitLimitReached);
  }
  // Nested arrays of 1,000 × 1,000 instances (within the instance limit) over 3 entities: 3 M
  // entities to handle, refused before the time goes (a fuzzing finding).
  try {
    load("xf -a 1000\nxf -a 1000\nc\nc\nc\nxf\nxf\n");
    ADD_FAILURE() << "accepted 3 M repeated entities";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("more than 1000000 times"), std::string::npos) << e.what();
    EXPECT_EQ(e.code(), kExitLimitReached);
  }
  EXPECT_THROW(load(kSquare, nullptr, MgfOptions{0, 1, 100}), std::invalid_argument);
  EXPECT_THROW(load(kSquare, nullptr, MgfOptions{0.02, 3, 100}), std::invalid_argument);
}

TEST(MgfReader, EveryTruncationLoadsOrIsRefusedCleanly) {
  // The test room in one file (its includes inlined), cut after every byte.
  auto lines = [](const std::string& file) {
    std::ifstream in(kTestData + file);
    std::stringstream all;
    all << in.rdbuf();
    return all.str();
  };
  std::string text = lines("/parts/materials.mgf") + lines("/room.mgf");
  text.erase(text.find("i parts/materials.mgf"), std::string("i parts/materials.mgf").size());
  const size_t lamp = text.find("i parts/lamp.mgf");
  text.replace(lamp, text.find('\n', lamp) - lamp, "xf -t 1 1.5 2.49 -a 2 -t 2 0 0\n" + lines("/parts/lamp.mgf") + "xf");
  const std::string dir = test_dir();
  size_t loaded = 0;
  for (size_t n = 0; n <= text.size(); ++n) {
    const std::string path = write(dir, "cut.mgf", text.substr(0, n));
    try {
      read_mgf(path);
      ++loaded;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
    }
  }
  EXPECT_GT(loaded, 0u);
  EXPECT_EQ(read_mgf(write(dir, "whole.mgf", text)).polygons.size(), read_mgf(kTestData + "/room.mgf").polygons.size());
}

// ---- the classic scenes -------------------------------------------------------------------------

// Counts what a plain scene file holds with no tool but string splitting: its f lines, and those
// whose current material (m NAME ... ed E) emits. Only for files without transforms, includes or
// primitives, which this checks.
void grep_count(const std::string& path, uint64_t& faces, uint64_t& emitting) {
  std::ifstream in(path);
  std::string line, current;
  std::map<std::string, bool> emits;
  faces = emitting = 0;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string kw, name;
    words >> kw;
    ASSERT_TRUE(kw != "xf" && kw != "i" && kw != "sph" && kw != "cyl" && kw != "cone" && kw != "ring" &&
                kw != "torus" && kw != "prism" && kw != "fh")
        << path << " is not plain: " << line;
    if (kw == "m" && words >> name) emits[current = name];  // a definition, or a selection
    if (kw == "ed") {
      double e = 0;
      words >> e;
      emits[current] = e > 0;
    }
    if (kw == "f") {
      ++faces;
      emitting += emits[current];
    }
  }
}

TEST(MgfReader, LoadsTheClassicScenes) {
  if (!fs::exists(kSharedScenes)) GTEST_SKIP() << kSharedScenes << " is absent";
  struct Expected {
    std::string file;
    uint64_t faces, emitting_faces, primitives, emitting_primitives;
    size_t polygons;  // 0: not checked
  };
  // Counted by hand and with an independent script that follows includes and arrays:
  // corridor: 14 f lines, 4 of them in xf arrays of 19, 10, 18 and 10 (the lights): 10 + 57 faces;
  // 2 cyl, 1 sph and 1 torus. Polygons: L-shaped floor and ceiling 4 triangles each, 5 wall and
  // door quads, 57 light quads, 2 triangles and a quad; cylinders 16 each, sphere 128, torus 256.
  // office: 319 f lines and 220 primitives under one unit transform; emitters: 2 fluorescent
  // panels and a light bulb (sph). hospital: hosp.mgf includes structure.mgf (which includes the
  // furniture) and the furniture again, with arrays.
  const Expected scenes[] = {
      {"cube.mgf", 66, 2, 0, 0, 66},
      {"corridor.mgf", 67, 57, 4, 0, 489},
      {"office3/office.mgf", 319, 2, 220, 1, 0},
      {"hospital/hosp.mgf", 4959, 76, 228, 0, 0},
  };
  for (const Expected& e : scenes) {
    SCOPED_TRACE(e.file);
    const std::string path = kSharedScenes + "/" + e.file;
    MgfStats stats;
    const auto t0 = std::chrono::steady_clock::now();
    MgfOptions collection;  // the hospital includes the collection's shared ../Materials
    collection.input_folder = kSharedScenes;
    const Scene s = read_mgf(path, collection, &stats);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    size_t emitting_polygons = 0;
    for (const Polygon& p : s.polygons) {
      for (int k = 0; k < p.count; ++k) ASSERT_TRUE(is_finite(p.v[k]));
      ASSERT_LT(p.material, s.materials.size());
      emitting_polygons += s.materials[p.material].emits();
    }
    for (const Material& m : s.materials) {
      ASSERT_TRUE(is_finite(m.reflectance) && is_finite(m.emission));
      ASSERT_LT(max_component(m.reflectance), 1.0);
      ASSERT_GE(std::min({m.reflectance.x, m.reflectance.y, m.reflectance.z, m.emission.x, m.emission.y, m.emission.z}), 0.0);
    }
    EXPECT_EQ(stats.faces, e.faces);
    EXPECT_EQ(stats.emitting_faces, e.emitting_faces);
    EXPECT_EQ(stats.primitives, e.primitives);
    EXPECT_EQ(stats.emitting_primitives, e.emitting_primitives);
    EXPECT_GE(emitting_polygons, e.emitting_faces + e.emitting_primitives);
    if (e.polygons) EXPECT_EQ(s.polygons.size(), e.polygons);
    std::printf("  %s: %llu faces (%llu emitting), %llu primitives, %zu polygons (%zu emitting), %zu materials, "
                "%llu files, %.3f s\n",
                e.file.c_str(), (unsigned long long)stats.faces, (unsigned long long)stats.emitting_faces,
                (unsigned long long)stats.primitives, s.polygons.size(), emitting_polygons, s.materials.size(),
                (unsigned long long)stats.files, seconds);
  }
  // cube.mgf is plain: its counts come from the file's lines.
  uint64_t faces = 0, emitting = 0;
  grep_count(kSharedScenes + "/cube.mgf", faces, emitting);
  MgfStats stats;
  const Scene cube = read_mgf(kSharedScenes + "/cube.mgf", {}, &stats);
  EXPECT_EQ(stats.faces, faces);
  EXPECT_EQ(stats.emitting_faces, emitting);
  EXPECT_EQ(cube.polygons.size(), faces);  // triangles and planar convex quads only
  // The corridor's 57 ceiling lights face down.
  const Scene corridor = read_mgf(kSharedScenes + "/corridor.mgf");
  for (const Polygon& p : corridor.polygons)
    if (corridor.materials[p.material].emits()) expect_near(polygon_normal(p), {0, 0, -1}, 1e-12);
}

}  // namespace
}  // namespace walkrad
