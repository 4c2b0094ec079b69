// Chunk priority (chunk_priority.h) on a made-up manifest: the chunk needed soonest first, then the
// larger part of the image, distance only between chunks no frame ahead sees; needed chunks on and
// off the path.
#include <gtest/gtest.h>

#include "walkrad/runtime/chunk_priority.h"

namespace walkrad {
namespace {

Bounds box(Vec3 lo, Vec3 hi) {
  Bounds b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

Viewpoint looking_down_minus_z(Vec3 position) {
  Viewpoint v;
  v.position = position;
  v.forward = {0, 0, -1};
  v.up = {0, 1, 0};
  v.yfov = 1.0;
  v.aspect = 1.0;
  return v;
}

// Five unit boxes along −z at z = −2, −4, … seen by a 4-frame path; chunk 4 sits behind the camera.
Manifest test_manifest() {
  Manifest m;
  for (int i = 0; i < 4; ++i) {
    ChunkInfo c;
    c.file = "chunk-" + std::to_string(i) + ".glb";
    c.bounds = box({-0.5, -0.5, -2.0 * (i + 1) - 0.5}, {0.5, 0.5, -2.0 * (i + 1) + 0.5});
    m.chunks.push_back(c);
  }
  ChunkInfo behind;
  behind.bounds = box({-0.5, -0.5, 4.5}, {0.5, 0.5, 5.5});
  m.chunks.push_back(behind);
  for (int f = 0; f < 4; ++f) m.viewpoints.push_back(looking_down_minus_z({0, 0, 0}));
  // importance[chunk][frame]: chunk 0 seen now (a little), chunk 1 in 2 frames, chunk 2 in 2 frames
  // too (more of the image), chunk 3 and the one behind never.
  m.chunks[0].importance = {0.1f, 0.1f, 0.0f, 0.0f};
  m.chunks[1].importance = {0.0f, 0.0f, 0.3f, 0.0f};
  m.chunks[2].importance = {0.0f, 0.0f, 0.6f, 0.6f};
  m.chunks[3].importance = {0.0f, 0.0f, 0.0f, 0.0f};
  m.chunks[4].importance = {0.0f, 0.0f, 0.0f, 0.0f};
  for (const ChunkInfo& c : m.chunks) m.bounds.extend(c.bounds);
  return m;
}

TEST(ChunkPriority, SoonestNeededFirstThenTheLargerPartOfTheImage) {
  const Manifest m = test_manifest();
  const std::vector<double> p = chunk_priorities(m, {m.viewpoints[0], size_t(0), false}, 3);
  // L = 3: (4 − k + importance / 2) / 4, importance widened to the frames beside: chunks 1 and 2,
  // seen at frame 2, count from frame 1 (k = 1).
  EXPECT_NEAR(p[0], (4 + 0.05) / 4, 1e-6);
  EXPECT_NEAR(p[1], (3 + 0.15) / 4, 1e-6);
  EXPECT_NEAR(p[2], (3 + 0.3) / 4, 1e-6);
  EXPECT_GT(p[0], p[2]);  // needed now, however little of the image it covers
  EXPECT_GT(p[2], p[1]);
  // Chunks no frame ahead sees come after every seen one, the nearer first.
  EXPECT_GT(std::min({p[0], p[1], p[2]}), std::max(p[3], p[4]));
  EXPECT_GT(p[4], p[3]);  // 4.5 m behind against 7.5 m ahead
  EXPECT_GT(p[3], 0.0);
}

TEST(ChunkPriority, LookaheadLimitsTheFramesConsidered) {
  const Manifest m = test_manifest();
  const std::vector<double> p = chunk_priorities(m, {m.viewpoints[0], size_t(0), false}, 0);
  EXPECT_LT(p[1], 1e-6);  // seen 2 frames ahead: beyond the lookahead and the frame beside
  EXPECT_LT(p[2], 1e-6);
  EXPECT_GT(p[0], 1.0);
}

TEST(ChunkPriority, APathThatLoopsLooksPastItsEnd) {
  const Manifest m = test_manifest();
  const std::vector<double> ends = chunk_priorities(m, {m.viewpoints[3], size_t(3), false}, 2);
  const std::vector<double> loops = chunk_priorities(m, {m.viewpoints[3], size_t(3), true}, 2);
  EXPECT_LT(ends[0], 1e-6);
  EXPECT_NEAR(loops[0], (3 - 1 + 0.05) / 3, 1e-6);  // frame 0 comes one frame after the last
}

TEST(ChunkPriority, OffThePathTheFrustumAndDistanceDecide) {
  const Manifest m = test_manifest();
  const std::vector<double> p = chunk_priorities(m, {m.viewpoints[0], std::nullopt, false}, 3);
  EXPECT_GT(p[0], p[1]);
  EXPECT_GT(p[1], p[2]);
  EXPECT_GT(p[3], p[4]);  // in front (7.5 m) before behind (4.5 m)
}

TEST(ChunkPriority, NeededOnThePathIsWhatTheViewpointAndItsNeighboursSee) {
  const Manifest m = test_manifest();
  EXPECT_EQ(chunks_needed(m, {m.viewpoints[0], size_t(0), false}), (std::vector<uint32_t>{0}));
  EXPECT_EQ(chunks_needed(m, {m.viewpoints[2], size_t(2), false}), (std::vector<uint32_t>{0, 1, 2}));  // 0: frame 1
  EXPECT_EQ(chunks_needed(m, {m.viewpoints[3], size_t(3), false}), (std::vector<uint32_t>{1, 2}));     // 1: frame 2
  // Off the path: what the frustum holds, whatever the importance says.
  EXPECT_EQ(chunks_needed(m, {m.viewpoints[0], std::nullopt, false}), (std::vector<uint32_t>{0, 1, 2, 3}));
}

TEST(ChunkPriority, FrustumTestIsConservative) {
  const Manifest m = test_manifest();
  const Viewpoint v = looking_down_minus_z({0, 0, 0});
  EXPECT_TRUE(bounds_in_frustum(v, m.bounds, box({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1})));  // around the eye
  EXPECT_TRUE(bounds_in_frustum(v, m.bounds, box({-100, -0.1, -3}, {100, 0.1, -2})));    // wider than the view
  EXPECT_FALSE(bounds_in_frustum(v, m.bounds, box({5, -0.5, -2}, {6, 0.5, -1})));        // off to the right
  EXPECT_FALSE(bounds_in_frustum(v, m.bounds, Bounds{}));
}

TEST(ChunkPriority, DistanceToBounds) {
  const Bounds b = box({0, 0, 0}, {1, 1, 1});
  EXPECT_DOUBLE_EQ(distance_to_bounds({0.5, 0.5, 0.5}, b), 0.0);
  EXPECT_DOUBLE_EQ(distance_to_bounds({3, 0.5, 0.5}, b), 2.0);
  EXPECT_DOUBLE_EQ(distance_to_bounds({4, 5, 0.5}, b), 5.0);
}

}  // namespace
}  // namespace walkrad
