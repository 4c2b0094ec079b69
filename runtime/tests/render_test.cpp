// Renders a small in-memory scene headless and checks pixels: placement (no mirror, no upside-down
// read-back), sRGB encoding, both faces drawn, depth test, black background.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "walkrad/formats/error.h"
#include "walkrad/runtime/camera.h"
#include "walkrad/runtime/framebuffer.h"
#include "walkrad/runtime/gpu_mesh.h"
#include "walkrad/runtime/headless_context.h"
#include "walkrad/runtime/image.h"
#include "walkrad/runtime/renderer.h"

namespace walkrad {
namespace {

constexpr int kSize = 64;

// Appends a triangle in the plane z with one colour, vertices in the order given.
void add_triangle(ChunkMesh& mesh, float z, const float (&xy)[6], const Vec3& color) {
  for (int v = 0; v < 3; ++v) {
    mesh.indices.push_back(uint32_t(mesh.vertex_count()));
    mesh.positions.insert(mesh.positions.end(), {xy[2 * v], xy[2 * v + 1], z});
    mesh.colors.insert(mesh.colors.end(), {float(color.x), float(color.y), float(color.z)});
  }
}

// Seen from (0, 0, 1) with a 90° field of view, the plane z = 0 fills NDC [−1, 1]² one to one:
// - a red triangle in the lower left, facing the camera;
// - a green quad in the lower right, one triangle facing the camera and one facing away;
// - a linear 0.5 grey quad in the upper right;
// - a blue quad further back (z = −0.5) on the left, drawn after the red triangle and partly behind it.
ChunkMesh test_scene() {
  ChunkMesh mesh;
  add_triangle(mesh, 0.0f, {-0.9f, -0.9f, -0.1f, -0.9f, -0.9f, 0.5f}, {1, 0, 0});
  add_triangle(mesh, 0.0f, {0.1f, -0.9f, 0.9f, -0.9f, 0.9f, -0.1f}, {0, 1, 0});
  add_triangle(mesh, 0.0f, {0.1f, -0.9f, 0.1f, -0.1f, 0.9f, -0.1f}, {0, 1, 0});  // clockwise: a back face
  add_triangle(mesh, 0.0f, {0.1f, 0.1f, 0.9f, 0.1f, 0.9f, 0.9f}, {0.5, 0.5, 0.5});
  add_triangle(mesh, 0.0f, {0.1f, 0.1f, 0.9f, 0.9f, 0.1f, 0.9f}, {0.5, 0.5, 0.5});
  add_triangle(mesh, -0.5f, {-0.9f, -0.9f, -0.1f, -0.9f, -0.1f, 0.9f}, {0, 0, 1});
  add_triangle(mesh, -0.5f, {-0.9f, -0.9f, -0.1f, 0.9f, -0.9f, 0.9f}, {0, 0, 1});
  return mesh;
}

Viewpoint test_view() {
  Viewpoint view;
  view.position = {0, 0, 1};
  view.forward = {0, 0, -1};
  view.up = {0, 1, 0};
  view.yfov = kPi / 2.0;
  view.aspect = 1.0;
  return view;
}

class RenderTest : public ::testing::Test {
 protected:
  Image render(const ChunkMesh& mesh) {
    Framebuffer target(kSize, kSize);
    target.bind();
    const GpuMesh gpu(mesh);
    const Renderer renderer;
    renderer.begin_frame(kSize, kSize);
    renderer.draw(gpu, view_projection(test_view(), mesh.bounds(), 1.0));
    return target.read_pixels();
  }

  HeadlessContext context_;
};

// The pixel under NDC (x, y) of the plane z = 0, y up; Image rows run from the top.
const uint8_t* at(const Image& image, double x, double y) {
  const int column = int(std::floor((x + 1.0) / 2.0 * image.width));
  const int row = int(std::floor((1.0 - y) / 2.0 * image.height));
  return image.pixel(column, row);
}

std::string rgb(const uint8_t* p) {
  return std::to_string(p[0]) + "," + std::to_string(p[1]) + "," + std::to_string(p[2]);
}

TEST_F(RenderTest, ShapesLandWhereTheCameraSeesThem) {
  const Image image = render(test_scene());
  ASSERT_EQ(image.width, kSize);
  ASSERT_EQ(image.height, kSize);
  EXPECT_EQ(rgb(at(image, -0.7, -0.7)), "255,0,0");    // red, lower left
  EXPECT_EQ(rgb(at(image, -0.95, 0.95)), "0,0,0");     // background, upper-left corner
  EXPECT_EQ(at(image, -0.95, 0.95)[3], 255);
  EXPECT_EQ(rgb(at(image, 0.95, -0.95)), "0,0,0");     // background, lower-right corner
  EXPECT_EQ(rgb(at(image, 0.8, -0.8)), "0,255,0");     // green, the triangle facing the camera
}

// The chunks' material is single-sided (glTF doubleSided false, as three.js also draws it): the two
// faces of a wall of no thickness must not both reach the depth test.
TEST_F(RenderTest, BackFacesAreCulled) {
  const Image image = render(test_scene());
  EXPECT_EQ(rgb(at(image, 0.2, -0.2)), "0,0,0");     // the clockwise half of the green quad
  EXPECT_EQ(rgb(at(image, 0.8, -0.8)), "0,255,0");   // its counter-clockwise half
}

TEST_F(RenderTest, LinearColourIsEncodedAsSrgb) {
  const Image image = render(test_scene());
  // sRGB(0.5) = 1.055 × 0.5^(1/2.4) − 0.055 = 0.7354 → 187.5 of 255.
  const uint8_t* grey = at(image, 0.5, 0.5);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(grey[c], 188, 1) << "channel " << c;
}

TEST_F(RenderTest, DepthTestKeepsTheNearerSurface) {
  const Image image = render(test_scene());
  // The blue quad is drawn last but lies behind the red triangle where they overlap.
  EXPECT_EQ(rgb(at(image, -0.5, -0.5)), "255,0,0");
  EXPECT_EQ(rgb(at(image, -0.3, 0.4)), "0,0,255");  // blue where nothing is in front of it
}

TEST_F(RenderTest, DisplayColoursAboveOneAreClamped) {
  ChunkMesh mesh;
  add_triangle(mesh, 0.0f, {-1.5f, -1.5f, 3.0f, -1.5f, -1.5f, 3.0f}, {4.0, 0.5, -1.0});
  const Image image = render(mesh);
  const uint8_t* p = at(image, -0.5, -0.5);
  EXPECT_EQ(p[0], 255);
  EXPECT_NEAR(p[1], 188, 1);
  EXPECT_EQ(p[2], 0);
}

TEST_F(RenderTest, MeshNeedsOneColourPerVertex) {
  ChunkMesh mesh = test_scene();
  mesh.colors.pop_back();
  EXPECT_THROW(GpuMesh{mesh}, std::invalid_argument);
}

TEST(WritePng, WritesAPngAndRefusesAMissingFolder) {
  Image image;
  image.width = 2;
  image.height = 1;
  image.rgba = {255, 0, 0, 255, 0, 255, 0, 255};
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "walkrad_runtime_write_png_test.png";
  write_png(file.string(), image);
  std::ifstream in(file, std::ios::binary);
  char signature[8] = {};
  in.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  std::filesystem::remove(file);
  EXPECT_THROW(write_png("/nonexistent-walkrad-folder/frame.png", image), OutputError);
}

}  // namespace
}  // namespace walkrad
