// Renders a real bake (the Cornell box) through Player, the path walkrad-view takes. Skipped until
// the bake exists: CMake's WALKRAD_RUNTIME_TEST_BAKE names it, the environment variable of the same
// name overrides it.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "walkrad/formats/error.h"
#include "walkrad/runtime/framebuffer.h"
#include "walkrad/runtime/headless_context.h"
#include "walkrad/runtime/player.h"
#include "bake_dirs.h"

namespace walkrad {
namespace {


// Mean of (red − green) over the columns [first, last) of the image: positive where red dominates.
double redness(const Image& image, int first, int last) {
  double sum = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = first; x < last; ++x) sum += double(image.pixel(x, y)[0]) - double(image.pixel(x, y)[1]);
  return sum / (double(last - first) * image.height);
}

TEST(BakeRender, CornellBoxShowsTheRedWallOnTheLeft) {
  const std::string dir = test_bake_dir("WALKRAD_RUNTIME_TEST_BAKE", WALKRAD_RUNTIME_TEST_BAKE);
  if (!std::filesystem::exists(std::filesystem::path(dir) / "manifest.json"))
    GTEST_SKIP() << "no bake at " << dir << " (set WALKRAD_RUNTIME_TEST_BAKE to a Cornell box bake)";

  HeadlessContext context;
  Player player = Player::open(dir);
  ASSERT_FALSE(player.manifest().viewpoints.empty()) << dir << ": the bake has no viewpoints";
  constexpr int kSize = 96;
  Framebuffer target(kSize, kSize);
  target.bind();
  player.draw(player.manifest().viewpoints.front(), kSize, kSize);
  const Image image = target.read_pixels();

  size_t lit = 0;
  for (size_t i = 0; i < image.rgba.size(); i += 4)
    if (image.rgba[i] > 16 || image.rgba[i + 1] > 16 || image.rgba[i + 2] > 16) ++lit;
  EXPECT_GT(lit, size_t(kSize * kSize) / 4) << "the frame is (nearly) black";

  const double left = redness(image, 0, kSize / 3), right = redness(image, kSize - kSize / 3, kSize);
  EXPECT_GT(left, right + 20.0) << "left third red − green " << left << ", right third " << right;

  const RenderStats& stats = player.stats();
  EXPECT_EQ(stats.chunks_resident, player.manifest().chunks.size());
  EXPECT_EQ(stats.chunks_total, player.manifest().chunks.size());
  EXPECT_GT(stats.bytes_loaded, 0u);
  EXPECT_EQ(stats.frame_cpu_ms.size(), 1u);
  EXPECT_GE(stats.time_to_first_frame_ms, stats.open_ms);
}

// A chunk that cannot be read fails on a worker; the error reaches the render thread naming the file.
TEST(BakeRender, AMissingChunkFileIsReportedByName) {
  const std::string dir = test_bake_dir("WALKRAD_RUNTIME_TEST_BAKE", WALKRAD_RUNTIME_TEST_BAKE);
  if (!std::filesystem::exists(std::filesystem::path(dir) / "manifest.json"))
    GTEST_SKIP() << "no bake at " << dir;
  const std::filesystem::path copy = std::filesystem::temp_directory_path() / "walkrad_runtime_missing_chunk";
  std::filesystem::remove_all(copy);
  std::filesystem::copy(dir, copy, std::filesystem::copy_options::recursive);
  HeadlessContext context;
  Player player = Player::open(copy.string());
  const std::filesystem::path gone = copy / player.manifest().chunks.front().file;
  std::filesystem::remove(gone);
  Framebuffer target(8, 8);
  target.bind();
  try {
    player.draw(player.manifest().viewpoints.front(), 8, 8);
    ADD_FAILURE() << "no error for the missing " << gone;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), gone.string());
  }
  std::filesystem::remove_all(copy);
}

}  // namespace
}  // namespace walkrad
