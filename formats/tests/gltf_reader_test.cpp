// The glTF reader on the Cornell box example: geometry, materials, emission, camera.
#include "walkrad/formats/gltf_reader.h"

#include <fstream>

#include <gtest/gtest.h>

#include "walkrad/formats/error.h"

namespace walkrad {
namespace {

const std::string kCornell = std::string(WALKRAD_SOURCE_DIR) + "/examples/cornell-box/cornell-box.gltf";

TEST(GltfReader, ReadsTheCornellBox) {
  const Scene s = read_gltf(kCornell);
  // 6 room quads + 2 blocks × 5 faces; every published quad that is planar stays one quad.
  size_t triangles = 0, quads = 0;
  for (const Polygon& p : s.polygons) (p.count == 4 ? quads : triangles) += 1;
  EXPECT_EQ(quads * 2 + triangles, 32u);
  EXPECT_GE(quads, 14u);
  ASSERT_EQ(s.materials.size(), 4u);
  // The light: radiance (17, 12, 4) → emitted radiosity π·L.
  const Material& light = s.materials[3];
  EXPECT_NEAR(light.emission.x, 17 * kPi, 1e-9);
  EXPECT_NEAR(light.emission.y, 12 * kPi, 1e-9);
  EXPECT_NEAR(light.emission.z, 4 * kPi, 1e-9);
  EXPECT_NEAR(s.materials[1].reflectance.x, 0.63, 1e-12);
  // Metres: the box is 0.556 m wide.
  const Bounds b = s.bounds();
  EXPECT_NEAR(b.hi.x, 0.556, 1e-6);
  EXPECT_NEAR(b.hi.y, 0.5488, 1e-6);
  // Every surface faces into the box: the floor's normal points up.
  ASSERT_EQ(s.cameras.size(), 1u);
  const Viewpoint& cam = s.cameras[0];
  EXPECT_NEAR(cam.position.z, -0.8, 1e-9);
  EXPECT_NEAR(cam.forward.z, 1.0, 1e-9);
  EXPECT_NEAR(cam.up.y, 1.0, 1e-9);
  EXPECT_NEAR(cam.yfov, 2 * std::atan(12.5 / 35), 1e-6);
}

TEST(GltfReader, EveryPolygonOfTheRoomFacesInwards) {
  const Scene s = read_gltf(kCornell);
  const Vec3 centre = s.bounds().center();
  for (const Polygon& p : s.polygons) {
    if (p.material == 3) continue;  // the light faces down, also inwards, but sits by the ceiling
    const Vec3 c = polygon_centroid(p);
    const bool room = c.y < 1e-3 || c.y > 0.548 || c.z > 0.559 || c.x < 1e-3 || c.x > 0.549;
    if (room) EXPECT_GT(dot(polygon_normal(p), centre - c), 0) << "polygon at " << c.x << " " << c.y << " " << c.z;
  }
}

void expect_refused(const std::string& path, const std::string& part) {
  try {
    read_scene(path);
    FAIL() << "accepted " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(GltfReader, RefusesMissingAndUnknownFiles) {
  expect_refused("/nonexistent/scene.gltf", "cannot open");
  expect_refused("/nonexistent/scene.obj", "unknown scene format");
}

TEST(GltfReader, RefusesATruncatedFile) {
  std::ifstream in(kCornell, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const std::string cut = testing::TempDir() + "truncated.gltf";
  std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 2));
  expect_refused(cut, "invalid glTF");
}

}  // namespace
}  // namespace walkrad
