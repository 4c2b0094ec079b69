// write_scene_gltf: an MGF scene converted to glTF reads back (read_gltf) with the same polygons,
// materials and viewpoints.
#include "walkrad/formats/scene_writer.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include <gtest/gtest.h>

#include "walkrad/formats/error.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/mgf_reader.h"

namespace walkrad {
namespace {

namespace fs = std::filesystem;
const std::string kRoom = std::string(WALKRAD_SOURCE_DIR) + "/tests/data/mgf/room.mgf";
const std::string kSharedScenes = std::string(WALKRAD_SOURCE_DIR) + "/../shared/scenes/mgf";

// The test room plus what MGF cannot say: a dim emitter (E/π below 1: no emissive strength) and a viewpoint.
Scene room() {
  Scene s = read_mgf(kRoom);
  s.materials.push_back({"dim", {0.1, 0.2, 0.3}, {0.5, 1.0, 1.5}});
  Polygon p;
  p.count = 3;
  p.v = {Vec3{1, 1, 2}, Vec3{1.5, 1, 2}, Vec3{1, 1.5, 2}};
  p.material = uint32_t(s.materials.size() - 1);
  s.polygons.push_back(p);
  Viewpoint v;
  v.name = "door";
  v.position = {0.3, 0.4, 1.6};
  v.forward = normalize(Vec3{1, 0.8, -0.1});
  v.up = normalize(cross(cross(v.forward, {0, 0, 1}), v.forward));
  v.yfov = 0.9;
  v.aspect = 1.5;
  s.cameras.push_back(v);
  return s;
}

// The largest distance between the polygons' vertices over the cyclic shifts that align them best.
double vertex_error(const Polygon& a, const Polygon& b) {
  if (a.count != b.count) return INFINITY;
  double best = INFINITY;
  for (int shift = 0; shift < a.count; ++shift) {
    double worst = 0;
    for (int k = 0; k < a.count; ++k) worst = std::max(worst, length(a.v[k] - b.v[(k + shift) % a.count]));
    best = std::min(best, worst);
  }
  return best;
}

void expect_same_scene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    SCOPED_TRACE(a.materials[i].name);
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(a.materials[i].reflectance[c], b.materials[i].reflectance[c], 1e-6);
      EXPECT_NEAR(a.materials[i].emission[c], b.materials[i].emission[c], 1e-6);
    }
  }
  // Every polygon once, with its material and its vertices (in order, up to where the loop starts),
  // found through a grid of centroids (cells of 1e-4 m, neighbours searched).
  ASSERT_EQ(a.polygons.size(), b.polygons.size());
  std::vector<bool> used(b.polygons.size(), false);
  std::map<std::array<long, 3>, std::vector<size_t>> grid;
  auto cell = [](const Vec3& c) { return std::array<long, 3>{std::lround(c.x * 1e4), std::lround(c.y * 1e4), std::lround(c.z * 1e4)}; };
  for (size_t j = 0; j < b.polygons.size(); ++j) grid[cell(polygon_centroid(b.polygons[j]))].push_back(j);
  for (const Polygon& p : a.polygons) {
    size_t found = b.polygons.size();
    const std::array<long, 3> c = cell(polygon_centroid(p));
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (size_t j : it->second)
            if (found == b.polygons.size() && !used[j] && b.polygons[j].material == p.material &&
                vertex_error(p, b.polygons[j]) <= 1e-6 * std::max(1.0, length(p.v[0])))
              found = j;
        }
    ASSERT_LT(found, b.polygons.size()) << "no match for a polygon of " << a.materials[p.material].name << " at "
                                        << polygon_centroid(p).x << " " << polygon_centroid(p).y << " "
                                        << polygon_centroid(p).z;
    used[found] = true;
  }
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (size_t i = 0; i < a.cameras.size(); ++i) {
    const Viewpoint &x = a.cameras[i], &y = b.cameras[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_LT(length(x.position - y.position), 1e-9);
    EXPECT_LT(length(x.forward - y.forward), 1e-9);
    EXPECT_LT(length(x.up - y.up), 1e-9);
    EXPECT_NEAR(x.yfov, y.yfov, 1e-9);
    EXPECT_NEAR(x.aspect, y.aspect, 1e-9);
  }
}

TEST(SceneWriter, RoundTripsAnMgfSceneThroughGlbAndGltf) {
  const Scene original = room();
  for (const std::string ext : {".glb", ".gltf"}) {
    SCOPED_TRACE(ext);
    const std::string path = testing::TempDir() + "walkrad-room" + ext;
    write_scene_gltf(original, path);
    const Scene back = read_gltf(path);
    EXPECT_EQ(back.dropped_degenerate, 0u);
    expect_same_scene(original, back);
  }
}

TEST(SceneWriter, RoundTripsTheClassicScenes) {
  if (!fs::exists(kSharedScenes)) GTEST_SKIP() << kSharedScenes << " is absent";
  for (const std::string name : {"cube.mgf", "corridor.mgf", "office3/office.mgf", "hospital/hosp.mgf"}) {
    SCOPED_TRACE(name);
    MgfOptions collection;  // the hospital includes the collection's shared ../Materials
    collection.input_folder = kSharedScenes;
    const Scene original = read_mgf(kSharedScenes + "/" + name, collection);
    const std::string path = testing::TempDir() + "walkrad-classic.glb";
    write_scene_gltf(original, path);
    expect_same_scene(original, read_gltf(path));
  }
}

TEST(SceneWriter, KeepsTrianglesThatShareAnEdgeApart) {
  // Two triangles of one material forming a planar convex quad: read_gltf would merge them if
  // they followed each other in one primitive.
  Scene s;
  s.materials.push_back({"grey", {0.5, 0.5, 0.5}, {}});
  Polygon a, b;
  a.v = {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}};
  b.v = {Vec3{0, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}};
  s.polygons = {a, b};
  const std::string path = testing::TempDir() + "walkrad-two-triangles.glb";
  write_scene_gltf(s, path);
  const Scene back = read_gltf(path);
  ASSERT_EQ(back.polygons.size(), 2u);
  expect_same_scene(s, back);
}

TEST(SceneWriter, RefusesOtherExtensionsAndUnwritablePaths) {
  const Scene s = room();
  EXPECT_THROW(write_scene_gltf(s, testing::TempDir() + "room.obj"), std::invalid_argument);
  EXPECT_THROW(write_scene_gltf(s, "/nonexistent-dir/room.glb"), OutputError);
}

}  // namespace
}  // namespace walkrad
