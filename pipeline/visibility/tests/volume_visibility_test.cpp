// Volumetric visibility in bakes: on a small dense hedge (examples/dense-hedge, 1,000 cubes),
// the wall behind it agrees with exact rays within 10% (RMS, as the walkthrough sees it) for 5× fewer
// rays; extinction.vdb is written, reused by a rebake of the same geometry, identical with 1 and 2
// threads; the effect plan turns volumes off where there are none.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "walkrad/testing/temp_dir_test.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/manifest.h"
#include "walkrad/accuracy/error_measures.h"
#include "walkrad/bake/bake.h"
#include "walkrad/output/bake_inspect.h"
#include "walkrad/accuracy/bake_sampler.h"
#include "walkrad/visibility/extinction_grid.h"

namespace walkrad {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

class VolumeBake : public test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    const std::string cmd = std::string("python3 ") + WALKRAD_SOURCE_DIR + "/examples/dense-hedge/make_dense_hedge.py --cubes 1000 '" +
                            dir_.string() + "' > /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
  }

  nlohmann::json bake_hedge(const std::string& name, std::map<std::string, std::string> effects = {}, int threads = 2,
                            double penumbra_ratio = 1.0) {
    BakeSettings s;
    s.volume_penumbra_ratio = penumbra_ratio;
    s.scene = (dir_ / "dense-hedge.glb").string();
    s.views = (dir_ / "dense-hedge-walkthrough.json").string();
    s.output = (dir_ / name).string();
    s.exposure = 1;
    s.threads = threads;
    s.progress = false;
    s.effects = std::move(effects);
    bake(s);
    std::ifstream in(s.output + "/report.json");
    return nlohmann::json::parse(in);
  }

  std::vector<double> wall_image(const std::string& name) {
    const fs::path bake_dir = dir_ / name;
    const Manifest m = read_manifest((bake_dir / "manifest.json").string());
    return BakeSampler::open(bake_dir.string()).luminance_image(m.viewpoints.at(0), 64);
  }
};

TEST_F(VolumeBake, WallAgreesWithExactRaysForFiveTimesFewerRays) {
  const nlohmann::json volume = bake_hedge("volume");
  const nlohmann::json exact = bake_hedge("exact", {{"volumes", "off"}});
  EXPECT_TRUE(volume["effects"]["volumes"]["on"].get<bool>()) << volume["effects"]["volumes"]["reason"];
  EXPECT_FALSE(exact["effects"]["volumes"]["on"].get<bool>());
  const auto& cv = volume["counts"];
  const auto& ce = exact["counts"];
  EXPECT_GT(cv["volume_links"].get<uint64_t>(), 0u);
  EXPECT_EQ(ce["volume_links"].get<uint64_t>(), 0u);
  EXPECT_GT(cv["grid_segments"].get<uint64_t>(), 0u);
  EXPECT_LT(5 * cv["visibility_rays"].get<uint64_t>(), ce["visibility_rays"].get<uint64_t>());
  EXPECT_EQ(volume["volumes"]["polygons"].get<uint64_t>(), 6000u);  // every cube, never the wall, floor or panel

  const std::vector<double> v = wall_image("volume"), e = wall_image("exact");
  const ErrorMeasures err = relative_errors(v, e);
  EXPECT_LT(err.rms, 0.10);

  // A rule that accepts no volume: every link exact, the same chunks as with volumes off.
  const nlohmann::json strict = bake_hedge("strict", {}, 2, 1e-9);
  EXPECT_EQ(strict["counts"]["volume_links"].get<uint64_t>(), 0u);
  EXPECT_EQ(strict["counts"]["visibility_rays"], ce["visibility_rays"]);
  EXPECT_EQ(slurp(dir_ / "strict" / "chunk-0000.glb"), slurp(dir_ / "exact" / "chunk-0000.glb"));
}

TEST_F(VolumeBake, GridIsWrittenReusedAndIdenticalWithOneOrTwoThreads) {
  const nlohmann::json first = bake_hedge("a", {}, 2);
  EXPECT_EQ(first["volumes"]["grid"], "built");
  ASSERT_TRUE(fs::exists(dir_ / "a" / "extinction.vdb"));
  const std::string grid = slurp(dir_ / "a" / "extinction.vdb");
  // Every file but report.json (which holds times), concatenated by name.
  auto outputs = [&](const std::string& name) {
    std::string all;
    for (const char* f : {"manifest.json", "chunk-0000.glb", "chunk-0001.glb", "chunk-0002.glb"})
      if (fs::exists(dir_ / name / f)) all += std::string(f) + ":" + slurp(dir_ / name / f);
    return all;
  };
  const std::string chunk = outputs("a");
  ASSERT_GT(chunk.size(), 1000u);

  const nlohmann::json again = bake_hedge("a", {}, 1);  // the same folder: the grid is reused
  EXPECT_EQ(again["volumes"]["grid"], "reused");
  EXPECT_EQ(slurp(dir_ / "a" / "extinction.vdb"), grid);
  EXPECT_EQ(outputs("a"), chunk);

  const nlohmann::json other = bake_hedge("b", {}, 1);  // another folder, one thread: built, same bytes
  EXPECT_EQ(other["volumes"]["grid"], "built");
  EXPECT_EQ(slurp(dir_ / "b" / "extinction.vdb"), grid);
  EXPECT_EQ(outputs("b"), chunk);
  EXPECT_EQ(other["counts"], first["counts"]);

  const ExtinctionGrid g = ExtinctionGrid::read((dir_ / "a" / "extinction.vdb").string());
  EXPECT_EQ(g.metadata("volume_polygons"), "6000");
  EXPECT_EQ(g.metadata("penumbra_ratio"), "1.0");
  testing::internal::CaptureStdout();
  inspect_bake((dir_ / "a").string(), "");
  const std::string printed = testing::internal::GetCapturedStdout();
  EXPECT_NE(printed.find("extinction.vdb: " + g.metadata("volume_clusters") + " volume clusters (6000 polygons)"), std::string::npos)
      << printed;

  // Without volumes, no grid in the folder (not even the previous one).
  bake_hedge("a", {{"volumes", "off"}});
  EXPECT_FALSE(fs::exists(dir_ / "a" / "extinction.vdb"));
}

TEST_F(VolumeBake, ForcingVolumesOnTheClassicMethodIsRefused) {
  BakeSettings s;
  s.scene = (dir_ / "dense-hedge.glb").string();
  s.output = (dir_ / "classic").string();
  s.method = Method::classic;
  s.progress = false;
  s.effects = {{"volumes", "on"}};
  try {
    bake(s);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), kExitBadArguments);
    EXPECT_NE(std::string(e.what()).find("volumes"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(dir_ / "classic"));
}

}  // namespace
}  // namespace walkrad
