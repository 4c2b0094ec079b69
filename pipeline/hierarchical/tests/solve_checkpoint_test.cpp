// The solve's state between rounds (solve_checkpoint.cpp): a solve resumed from any round's saved
// state ends exactly where one that ran through ends, and damaged bytes are refused. The bake-level
// checkpoint file, kills and ranks: tests/cli/test_checkpoint.py.
#include <cstring>
#include <functional>
#include <map>

#include <gtest/gtest.h>

#include "walkrad/formats/scene_reader.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/scene/cluster_tree.h"

namespace walkrad {
namespace {

const std::string kCornell = std::string(WALKRAD_SOURCE_DIR) + "/examples/cornell-box/cornell-box.gltf";

TEST(SolveCheckpoint, ResumedFromAnyRoundEndsWhereTheSolveThatRanThroughEnds) {
  const Scene scene = read_scene(kCornell);
  const ClusterTree tree = build_cluster_tree(scene);
  const RayScene rays(scene);
  HierarchicalSettings s;
  s.error = 0.4;  // a round trip of the state, not accuracy: the draft preset's rounds suffice
  std::map<int, std::vector<uint8_t>> saved;
  s.save_round = [&](int rounds, const std::function<void(ByteWriter&)>& write_state) {
    // Through the streaming writer, as checkpoint files are written, in pieces.
    std::vector<uint8_t>& bytes = saved[rounds];
    ByteWriter out([&](const uint8_t* p, size_t n) { bytes.insert(bytes.end(), p, p + n); });
    write_state(out);
    out.flush();
  };
  Hierarchy through(scene, tree);
  HierarchicalStats stats;
  solve_hierarchical(through, rays, s, stats);
  ASSERT_TRUE(stats.converged);
  ASSERT_GE(saved.size(), 4u);
  ASSERT_EQ(saved.rbegin()->first, int(stats.iterations.size()));

  HierarchicalSettings r = s;
  r.save_round = {};
  for (const auto& [round, state] : saved) {
    Hierarchy h(scene, tree);
    HierarchicalStats resumed;
    // Read back through the streaming reader, in pieces, as checkpoint files are.
    size_t at = 0;
    ByteReader in([&](uint8_t* dst, size_t n) { std::memcpy(dst, state.data() + at, n), at += n; }, state.size());
    r.resume = &in;
    solve_hierarchical(h, rays, r, resumed);
    ASSERT_EQ(h.nodes().size(), through.nodes().size()) << "after round " << round;
    size_t differ = 0;
    for (size_t i = 0; i < h.nodes().size(); ++i) {
      const HNode &a = h.nodes()[i], &b = through.nodes()[i];
      differ += std::memcmp(&a.B, &b.B, sizeof(Vec3)) != 0 || a.links.size() != b.links.size() || a.error != b.error;
    }
    EXPECT_EQ(differ, 0u) << "resumed after round " << round;
    EXPECT_EQ(resumed.links, stats.links);
    EXPECT_EQ(resumed.rays, stats.rays);
    EXPECT_EQ(resumed.iterations.size(), stats.iterations.size());
    EXPECT_TRUE(resumed.converged);
  }

  // Cut short, or with bytes to spare: refused before anything is solved.
  const std::vector<uint8_t>& some = saved.begin()->second;
  for (const std::vector<uint8_t>& bad : {std::vector<uint8_t>(some.begin(), some.begin() + long(some.size() / 2)),
                                          [&] { auto v = some; v.push_back(0); return v; }()}) {
    Hierarchy h(scene, tree);
    HierarchicalStats st;
    ByteReader in(bad);
    r.resume = &in;
    EXPECT_THROW(solve_hierarchical(h, rays, r, st), ByteFormatError);
  }
}

}  // namespace
}  // namespace walkrad
