// Streaming a real bake (the office floor fixture, cut into 32 chunks) along its walkthrough with a
// budget of half its chunks' bytes: chunks are read and decoded on the loader's workers only, the
// resident bytes stay within the budget, chunks get evicted and come back, and every frame is the
// one drawn with everything resident. (tests/cli/test_streaming.py checks the same through
// walkrad-view at playback speed, with no chunk missing.)
#include <filesystem>
#include <string>
#include <set>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "walkrad/runtime/framebuffer.h"
#include "walkrad/runtime/headless_context.h"
#include "walkrad/runtime/player.h"
#include "bake_dirs.h"

namespace walkrad {
namespace {

constexpr int kHeight = 48;

struct Playthrough {
  std::vector<Image> frames;
  RenderStats stats;
  std::set<std::thread::id> decode_threads;
  uint64_t resident_bytes_all = 0;  // display bytes of every chunk, once all are resident
};

Playthrough play(const std::string& dir, const StreamSettings& settings) {
  Player player = Player::open(dir, settings);
  const std::vector<Viewpoint>& views = player.manifest().viewpoints;
  const int width = int(kHeight * views.front().aspect);
  Framebuffer target(width, kHeight);
  target.bind();
  Playthrough out;
  for (size_t i = 0; i < views.size(); ++i) {
    player.update(CameraPlace{views[i], i, false});
    player.draw(width, kHeight, MissPolicy::kWait);
    out.frames.push_back(target.read_pixels());
  }
  out.stats = player.stats();
  out.decode_threads = player.cache().decode_threads();
  if (out.stats.chunks_resident == out.stats.chunks_total) out.resident_bytes_all = out.stats.resident_bytes;
  return out;
}

class Streaming : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test_bake_dir("WALKRAD_RUNTIME_OFFICE_BAKE", WALKRAD_RUNTIME_OFFICE_BAKE);
    if (!std::filesystem::exists(std::filesystem::path(dir_) / "manifest.json"))
      GTEST_SKIP() << "no bake at " << dir_ << " (set WALKRAD_RUNTIME_OFFICE_BAKE to an office-floor bake)";
  }
  std::string dir_;
  HeadlessContext context_;
};

TEST_F(Streaming, HalfTheBytesGiveTheSameFramesWithinTheBudget) {
  const Playthrough full = play(dir_, StreamSettings{});
  ASSERT_EQ(full.stats.chunks_resident, full.stats.chunks_total) << "with no budget every chunk stays";
  ASSERT_GE(full.stats.chunks_total, 8u) << dir_ << ": the fixture should cut the bake into at least 8 chunks";

  StreamSettings half;
  half.budget_bytes = full.resident_bytes_all / 2;
  const Playthrough streamed = play(dir_, half);
  EXPECT_LE(streamed.stats.max_resident_bytes, half.budget_bytes);
  EXPECT_GT(streamed.stats.chunk_evictions, 0u) << "the path should need more than the budget holds";
  EXPECT_LT(streamed.stats.chunks_resident, full.stats.chunks_total);
  ASSERT_EQ(streamed.frames.size(), full.frames.size());
  for (size_t i = 0; i < full.frames.size(); ++i)
    ASSERT_EQ(streamed.frames[i].rgba, full.frames[i].rgba) << "frame " << i << " differs from the full bake's";
}

TEST_F(Streaming, DecodingNeverRunsOnTheRenderThread) {
  StreamSettings settings;
  settings.worker_threads = 2;
  Player player = Player::open(dir_, settings);
  const Viewpoint& view = player.manifest().viewpoints.front();
  Framebuffer target(kHeight, kHeight);
  target.bind();
  // Off the path, a wait for every chunk in the frustum: the render thread blocks, workers decode.
  player.draw(view, kHeight, kHeight);
  for (size_t i = 0; i < player.manifest().viewpoints.size(); i += 10) {
    player.update(CameraPlace{player.manifest().viewpoints[i], i, false});
    player.draw(kHeight, kHeight, MissPolicy::kWait);
  }
  const std::set<std::thread::id> threads = player.cache().decode_threads();
  EXPECT_GT(player.stats().chunk_loads, 0u);
  EXPECT_FALSE(threads.empty());
  EXPECT_EQ(threads.count(std::this_thread::get_id()), 0u) << "read_chunk ran on the render thread";
  EXPECT_LE(threads.size(), size_t(settings.worker_threads));
}

TEST_F(Streaming, ABudgetTooSmallForAFrameLeavesItsChunksMissingWithoutExceedingIt) {
  StreamSettings tiny;
  tiny.budget_bytes = 64;  // less than any chunk (a glTF header alone is 12 bytes, its JSON more)
  Player player = Player::open(dir_, tiny);
  Framebuffer target(kHeight, kHeight);
  target.bind();
  player.update(CameraPlace{player.manifest().viewpoints.front(), size_t(0), false});
  player.draw(kHeight, kHeight, MissPolicy::kWait);  // must return, not wait for ever
  EXPECT_EQ(player.stats().chunks_resident, 0u);
  EXPECT_LE(player.stats().max_resident_bytes, tiny.budget_bytes);
}

}  // namespace
}  // namespace walkrad
