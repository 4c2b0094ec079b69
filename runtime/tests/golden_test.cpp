// The Cornell box bake rendered headless from its camera, against tests/golden/cornell-box.png:
// PSNR ≥ 40 dB (llvmpipe is deterministic; the margin allows other Mesa versions and drivers).
// WALKRAD_UPDATE_GOLDEN=1 rewrites the golden instead (after a deliberate change to the bake or the
// renderer; look at the new image before committing it).
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "walkrad/runtime/framebuffer.h"
#include "walkrad/runtime/headless_context.h"
#include "walkrad/runtime/image.h"
#include "walkrad/runtime/player.h"
#include "bake_dirs.h"

namespace walkrad {
namespace {

constexpr int kSize = 256;
constexpr double kMinPsnr = 40.0;

TEST(Golden, CornellBoxFromItsCamera) {
  const std::string dir = test_bake_dir("WALKRAD_RUNTIME_TEST_BAKE", WALKRAD_RUNTIME_TEST_BAKE);
  if (!std::filesystem::exists(std::filesystem::path(dir) / "manifest.json"))
    GTEST_SKIP() << "no bake at " << dir << " (set WALKRAD_RUNTIME_TEST_BAKE to a Cornell box bake)";
  HeadlessContext context;
  Player player = Player::open(dir);
  ASSERT_FALSE(player.manifest().viewpoints.empty());
  Framebuffer target(kSize, kSize);
  target.bind();
  player.draw(player.manifest().viewpoints.front(), kSize, kSize);
  const Image image = target.read_pixels();

  const std::string golden = std::string(WALKRAD_GOLDEN_DIR) + "/cornell-box.png";
  const char* update = std::getenv("WALKRAD_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    write_png(golden, image);
    GTEST_SKIP() << "rewrote " << golden;
  }
  ASSERT_TRUE(std::filesystem::exists(golden)) << golden << " is missing: run with WALKRAD_UPDATE_GOLDEN=1";
  const Image expected = read_png(golden);
  ASSERT_EQ(expected.width, kSize);
  ASSERT_EQ(expected.height, kSize);
  const double db = psnr(expected, image);
  if (db < kMinPsnr) write_png((std::filesystem::temp_directory_path() / "cornell-box-actual.png").string(), image);
  EXPECT_GE(db, kMinPsnr) << "against " << golden << "; this render is in " << std::filesystem::temp_directory_path()
                          << "/cornell-box-actual.png (WALKRAD_UPDATE_GOLDEN=1 accepts it)";
}

TEST(Golden, PsnrOfKnownDifferences) {
  Image a;
  a.width = 2;
  a.height = 1;
  a.rgba = {10, 20, 30, 255, 40, 50, 60, 255};
  Image b = a;
  EXPECT_TRUE(std::isinf(psnr(a, b)));
  b.rgba[0] += 6;  // one channel of six off by 6: MSE = 36 / 6 = 6
  EXPECT_NEAR(psnr(a, b), 10.0 * std::log10(255.0 * 255.0 / 6.0), 1e-9);
  b.width = 1;
  EXPECT_THROW(psnr(a, b), std::invalid_argument);
}

}  // namespace
}  // namespace walkrad
