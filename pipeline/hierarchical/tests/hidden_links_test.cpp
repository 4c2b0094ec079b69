// Links that see nothing: a link whose every ray is blocked is dropped where its occlusion is proven
// (occlusion_proof.h: a wall between two rooms), else kept at 0, cast again once with more rays, and
// refined while what it might carry matters (refinement.h, Refinement::unresolved); a pair with a long
// candidate list is probed before it is split (HierarchicalSettings::probe_entries).
#include <cmath>
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/scene/cluster_tree.h"

namespace walkrad {
namespace {

// Two closed rooms back to back, a wall 0.1 m thick between them, a lamp under the lit room's ceiling.
// Every link across the wall is proven hidden (the wall's face covers the shaft) and dropped: none is
// kept, refined or sent down to the children of a lit element that splits for the lamp's sake (without
// proofs, such links are cast again and split: each level casts 4 times the rays to find nothing;
// office-floor's 16 rooms would hold 3.2 M of them, 123 M of its 882 M rays).
Scene two_rooms() {
  Scene s = test::closed_box(4.0, {0.6, 0.6, 0.6}, {0, 0, 0});
  const size_t lit_faces = s.polygons.size();
  for (size_t k = 0; k < lit_faces; ++k) {  // the dark room, 0.1 m along x
    Polygon p = s.polygons[k];
    for (int c = 0; c < p.count; ++c) p.v[size_t(c)].x += 4.1;
    s.polygons.push_back(p);
  }
  s.materials.push_back({"lamp", {0, 0, 0}, {50, 50, 50}});
  Polygon lamp = test::quad({1.7, 3.99, 1.7}, {2.3, 3.99, 1.7}, {2.3, 3.99, 2.3}, {1.7, 3.99, 2.3}, 1);
  if (polygon_normal(lamp).y > 0) std::swap(lamp.v[1], lamp.v[3]);  // emits downwards
  s.polygons.push_back(lamp);
  return s;
}

TEST(Hierarchical, ALinkThroughAWallIsProvenHiddenAndDropped) {
  Scene s = two_rooms();
  const size_t lit_faces = 6, dark_end = 12;
  for (const double error : {HierarchicalSettings{}.error, 0.05}) {
    const ClusterTree tree = build_cluster_tree(s);
    const RayScene rays(s);
    Hierarchy h(s, tree);
    HierarchicalSettings settings;
    settings.error = error;
    HierarchicalStats stats;
    solve_hierarchical(h, rays, settings, stats);
    auto dark = [&](const HNode& n) { return !n.cluster && n.polygon >= lit_faces && n.polygon < dark_end; };
    size_t lit_splits = 0, across = 0, across_below = 0;
    for (const HNode& n : h.nodes()) {
      if (n.cluster) continue;
      if (dark(n)) {
        EXPECT_EQ(n.child_count, 0u) << "a dark room's element split, --error " << error;
        EXPECT_EQ(max_component(n.B), 0.0);
      } else if (n.child_count) {
        ++lit_splits;
      }
      for (const Link& l : n.links) {
        const HNode& src = h[l.source];
        const bool src_dark = src.cluster ? src.bounds.lo.x > 4.05 : dark(src);
        if (src_dark == dark(n) || (src.bounds.hi.x > 4.05 && src.bounds.lo.x < 4.05)) continue;
        ++across;
        across_below += n.depth > 0;
        EXPECT_EQ(l.F, 0.0);
      }
    }
    std::printf("--error %.2f: %zu lit elements split, %zu links across the wall (%zu below a root), %llu proven hidden, %llu rays\n",
                error, lit_splits, across, across_below, static_cast<unsigned long long>(stats.proven_hidden),
                static_cast<unsigned long long>(stats.rays));
    EXPECT_GT(lit_splits, 0u);  // the lamp's light varies over the lit room: its elements split
    EXPECT_GT(stats.proven_hidden, 0u);
    EXPECT_EQ(across, 0u) << "--error " << error;
  }
}

struct Solved {
  HierarchicalStats stats;
  double dark = 0;               // the dark room's area-weighted mean luminance
  std::vector<double> leaves;    // every leaf's luminance, in node order
};

// The scene solved at the default settings but probe_entries, on so many threads.
Solved solve(const Scene& s, size_t probe_entries, int threads, double dark_from_x) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const ClusterTree tree = build_cluster_tree(s);
  const RayScene rays(s);
  Hierarchy h(s, tree);
  HierarchicalSettings settings;
  settings.probe_entries = probe_entries;
  Solved out;
  solve_hierarchical(h, rays, settings, out.stats);
  double area = 0;
  for (const HNode& n : h.nodes()) {
    if (n.cluster) continue;
    const bool dark = n.center.x > dark_from_x;
    if (n.child_count == 0) {
      out.leaves.push_back(luminance(n.B));
      if (dark) out.dark += luminance(n.B) * n.area, area += n.area;
    }
  }
  out.dark /= area;
  return out;
}

// A door in the wall, 1 × 2 m, the lamp in one room: what the dark room gets all comes through it, so a
// probe that called a pair hidden where it sees the door would darken it. Every pair with a parent's
// list probed (probe_entries 0): the pairs the wall hides are linked where they are, with fewer links
// and rays than split level by level, the room's mean stays within 3% of the unprobed solve's (their
// links draw other rays: 0.8% apart; the hidden pairs dropped instead of linked, 11.7%), and the result
// is the same on 1 and 2 threads (the probes' rays are drawn per pair).
TEST(Hierarchical, ProbesKeepTheLightThroughADoor) {
  Scene s = two_rooms();
  for (const double x : {4.0, 4.1}) {  // each room's wall at the door: the wall around a door at z 1.5-2.5, y 0-2
    for (size_t k = 0; k < s.polygons.size(); ++k) {
      const Polygon& p = s.polygons[k];
      if (!(std::fabs(polygon_centroid(p).x - x) < 1e-9)) continue;
      const Vec3 n = polygon_normal(p);
      const uint32_t m = p.material;
      s.polygons.erase(s.polygons.begin() + long(k));
      auto add = [&](double y0, double y1, double z0, double z1) {
        Polygon q = test::quad({x, y0, z0}, {x, y1, z0}, {x, y1, z1}, {x, y0, z1}, m);
        if (dot(polygon_normal(q), n) < 0) std::swap(q.v[1], q.v[3]);
        s.polygons.push_back(q);
      };
      add(0, 4, 0, 1.5);
      add(0, 4, 2.5, 4);
      add(2, 4, 1.5, 2.5);
      break;
    }
  }
  // The door's jambs, lintel and sill across the wall's 0.1 m.
  auto side = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec3 facing) {
    Polygon q = test::quad(a, b, c, d, 0);
    if (dot(polygon_normal(q), facing) < 0) std::swap(q.v[1], q.v[3]);
    s.polygons.push_back(q);
  };
  side({4.0, 0, 1.5}, {4.1, 0, 1.5}, {4.1, 2, 1.5}, {4.0, 2, 1.5}, {0, 0, 1});
  side({4.0, 0, 2.5}, {4.1, 0, 2.5}, {4.1, 2, 2.5}, {4.0, 2, 2.5}, {0, 0, -1});
  side({4.0, 2, 1.5}, {4.1, 2, 1.5}, {4.1, 2, 2.5}, {4.0, 2, 2.5}, {0, -1, 0});
  const Solved probed = solve(s, 0, 2, 4.05), plain = solve(s, std::numeric_limits<size_t>::max(), 2, 4.05);
  std::printf("dark room: %.5f probed (%llu pairs, %llu hidden, %llu links, %llu rays), %.5f unprobed (%llu links, %llu rays)\n",
              probed.dark, static_cast<unsigned long long>(probed.stats.probed_pairs),
              static_cast<unsigned long long>(probed.stats.probe_hidden), static_cast<unsigned long long>(probed.stats.links),
              static_cast<unsigned long long>(probed.stats.rays), plain.dark,
              static_cast<unsigned long long>(plain.stats.links), static_cast<unsigned long long>(plain.stats.rays));
  EXPECT_EQ(plain.stats.probed_pairs, 0u);
  EXPECT_GT(probed.stats.probe_hidden, 0u);
  EXPECT_GT(probed.stats.probed_pairs, probed.stats.probe_hidden);  // some see the door
  EXPECT_LT(probed.stats.links, plain.stats.links);
  EXPECT_LT(probed.stats.rays, plain.stats.rays);
  EXPECT_GT(plain.dark, 0.0);
  EXPECT_NEAR(probed.dark, plain.dark, 0.03 * plain.dark);
  EXPECT_EQ(solve(s, 0, 1, 4.05).leaves, probed.leaves);
}

}  // namespace
}  // namespace walkrad
