// The Cornell box baked end to end by the classic method: colour bleeds from the red and green walls
// onto the floor beside them, the manifest describes the output, and the bake does not depend on the
// thread count.
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "walkrad/formats/bake_folder.h"
#include "walkrad/formats/chunk.h"
#include "walkrad/formats/manifest.h"
#include "walkrad/bake/bake.h"

namespace walkrad {
namespace {

namespace fs = std::filesystem;
const std::string kCornell = std::string(WALKRAD_SOURCE_DIR) + "/examples/cornell-box/cornell-box.gltf";

BakeSettings coarse(const std::string& out, int threads) {
  BakeSettings s;
  s.scene = kCornell;
  s.output = out;
  s.element_size = 0.05;
  s.threads = threads;
  s.progress = false;
  return s;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

class CornellBake : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One folder per process: ctest runs each test in its own process, possibly at the same time.
    dir_ = fs::path(testing::TempDir()) / ("walkrad-cornell-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    bake(coarse((dir_ / "t2").string(), 2));  // the one-thread bake only where a test compares with it
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
};
fs::path CornellBake::dir_;

TEST_F(CornellBake, ManifestDescribesTheOutput) {
  const Manifest m = read_manifest((dir_ / "t2/manifest.json").string());
  ASSERT_GE(m.chunks.size(), 1u);
  uint64_t triangles = 0;
  for (const ChunkInfo& c : m.chunks) {
    EXPECT_EQ(c.bytes, fs::file_size(dir_ / "t2" / c.file));
    EXPECT_EQ(c.triangles, read_chunk((dir_ / "t2" / c.file).string()).triangle_count());
    ASSERT_EQ(c.importance.size(), 1u);
    triangles += c.triangles;
  }
  EXPECT_EQ(triangles, read_bake_mesh((dir_ / "t2").string()).triangle_count());
  ASSERT_EQ(m.viewpoints.size(), 1u);  // the scene's camera is the walkthrough
  EXPECT_GT(m.exposure, 0);
  EXPECT_TRUE(fs::exists(dir_ / "t2/report.json"));
}

// Average R/G of floor vertices in a band of x (the red wall stands at x ≈ 0.55, the green at x = 0).
double floor_red_over_green(const ChunkMesh& mesh, double x0, double x1) {
  double r = 0, g = 0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double x = mesh.positions[3 * v], y = mesh.positions[3 * v + 1], z = mesh.positions[3 * v + 2];
    if (y > 1e-6 || x < x0 || x > x1 || z > 0.5) continue;  // floor
    r += mesh.radiosity[3 * v];
    g += mesh.radiosity[3 * v + 1];
  }
  return r / g;
}

TEST_F(CornellBake, ColourBleedsFromTheWallsOntoTheFloor) {
  const ChunkMesh mesh = read_bake_mesh((dir_ / "t2").string());
  const double near_red = floor_red_over_green(mesh, 0.45, 0.56);
  const double middle = floor_red_over_green(mesh, 0.0, 0.56);  // the whole floor
  const double near_green = floor_red_over_green(mesh, 0.0, 0.1);
  EXPECT_GT(near_red, 1.1 * middle);
  EXPECT_LT(near_green, middle / 1.1);
}

TEST_F(CornellBake, SameResultWithOneAndTwoThreads) {
  bake(coarse((dir_ / "t1").string(), 1));
  EXPECT_EQ(read_bytes((dir_ / "t1/manifest.json").string()), read_bytes((dir_ / "t2/manifest.json").string()));
  for (const ChunkInfo& c : read_manifest((dir_ / "t1/manifest.json").string()).chunks)
    EXPECT_EQ(read_bytes((dir_ / "t1" / c.file).string()), read_bytes((dir_ / "t2" / c.file).string())) << c.file;
}

}  // namespace
}  // namespace walkrad
