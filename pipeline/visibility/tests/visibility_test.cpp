// Visibility: shaft culling (Haines & Wallace) is conservative and lets unobstructed pairs skip rays;
// contact splitting and ray offsets keep light from leaking under a wall standing on the floor.
#include <algorithm>

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/scene/contact_split.h"
#include "walkrad/classic/form_factor_matrix.h"
#include "walkrad/classic/gauss_seidel.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/core/sampling.h"
#include "walkrad/visibility/shaft.h"
#include "walkrad/classic/subdivision.h"

namespace walkrad {
namespace {

using test::quad;

Bounds box(Vec3 lo, Vec3 hi) {
  Bounds b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

// Every box a segment between the two boxes passes through overlaps the shaft (conservative), and
// boxes off to the side do not.
TEST(Shaft, IsConservativeAndCulls) {
  const Bounds a = box({0, 0, 0}, {1, 1, 1}), b = box({4, 3, 0}, {5, 4, 1});
  const Shaft shaft(a, b);
  EXPECT_GT(shaft.plane_count(), 0);
  Rng rng(7);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p(rng.uniform(), rng.uniform(), rng.uniform());
    const Vec3 q = Vec3(4, 3, 0) + Vec3(rng.uniform(), rng.uniform(), rng.uniform());
    const Vec3 x = p + (q - p) * rng.uniform();
    ASSERT_TRUE(shaft.overlaps(box(x, x + Vec3(1e-3, 1e-3, 1e-3))));
  }
  EXPECT_FALSE(shaft.overlaps(box({4, 0, 0}, {5, 1, 1})));  // the empty corner of the hull
  EXPECT_FALSE(shaft.overlaps(box({0, 3, 0}, {1, 4, 1})));  // the other empty corner
  EXPECT_TRUE(shaft.overlaps(box({2.4, 1.9, 0.4}, {2.6, 2.1, 0.6})));
}

// A compact candidate list (whole tree nodes as one entry) stands for exactly the polygons the
// plain search finds, in the same order, from the tree and filtered from a parent link's list, with
// the ends' own polygons excluded; and it is shorter where clusters lie wholly inside the shaft.
TEST(Shaft, CompactListsExpandToThePlainSearch) {
  Scene scene;
  Rng rng(11);
  Vec3 group;
  for (int k = 0; k < 3000; ++k) {  // 100 groups of 30 small quads in a 10 m cube, some flat on z = 0
    if (k % 30 == 0) group = Vec3(10 * rng.uniform(), 10 * rng.uniform(), k % 90 ? 10 * rng.uniform() : 0.0);
    const Vec3 o = group + Vec3(0.5 * rng.uniform(), 0.5 * rng.uniform(), group.z > 0 ? 0.5 * rng.uniform() : 0.0);
    const double s = 0.02 + 0.05 * rng.uniform();
    scene.polygons.push_back(quad(o, o + Vec3(s, 0, 0), o + Vec3(s, s, 0), o + Vec3(0, s, 0)));
  }
  const ClusterTree tree = build_cluster_tree(scene);
  size_t entries = 0, polygons = 0;
  for (int trial = 0; trial < 200; ++trial) {
    auto random_box = [&](double size) {
      const Vec3 lo(10 * rng.uniform(), 10 * rng.uniform(), trial % 4 ? 10 * rng.uniform() : 0.0);
      return box(lo, lo + Vec3(size * rng.uniform(), size * rng.uniform(), trial % 4 ? size * rng.uniform() : 0.0));
    };
    const Bounds a = random_box(4), b = random_box(4);
    const uint32_t ex_a = uint32_t(rng.uniform() * 3000), ex_b = trial % 2 ? UINT32_MAX : uint32_t(rng.uniform() * 3000);
    const Shaft parent(a, b);
    const std::vector<uint32_t> compact = compact_candidates(tree, parent, ex_a, ex_b);
    const std::vector<uint32_t> plain = shaft_candidates(tree, parent, ex_a, ex_b);
    ASSERT_EQ(expand_candidates(tree, compact, ex_a, ex_b), plain) << trial;
    ASSERT_EQ(candidate_count(tree, compact, ex_a, ex_b), plain.size()) << trial;
    entries += compact.size();
    polygons += plain.size();
    // A child link: a quarter of one end, its own polygon excluded as well.
    Bounds child = a;
    child.hi = a.lo + (a.hi - a.lo) * 0.5;
    const Shaft inner(child, b);
    const uint32_t ex_c = uint32_t(rng.uniform() * 3000);
    const std::vector<uint32_t> filtered = filter_compact_candidates(tree, inner, compact, ex_c, ex_b);
    for (const size_t limit : {size_t(1), size_t(5), size_t(65), size_t(1) << 30})  // counted without the list
      ASSERT_EQ(count_compact_candidates(tree, inner, compact, ex_c, ex_b, limit),
                std::min(limit, candidate_count(tree, filtered, ex_c, ex_b))) << trial;
    std::vector<uint32_t> expected = shaft_candidates(tree, inner, ex_c, ex_b);
    // The parent's exclusion holds below it (a child element keeps its parent's polygon).
    expected.erase(std::remove(expected.begin(), expected.end(), ex_a), expected.end());
    std::vector<uint32_t> got = expand_candidates(tree, filtered, ex_c, ex_b);
    got.erase(std::remove(got.begin(), got.end(), ex_a), got.end());
    ASSERT_EQ(got, expected) << trial;
  }
  EXPECT_GT(polygons, 10000u);
  EXPECT_LT(entries * 2, polygons);  // whole groups as one entry
}

// A room of two halves split by a wall that stands on the floor and touches the ceiling; the light
// is on one side. The dark side must stay dark: below 1e-4 of the lit side.
TEST(LightLeak, WallOnTheFloorLetsNoLightThrough) {
  Scene s;
  s.source = "split room";
  s.materials = {{"white", {0.7, 0.7, 0.7}, {0, 0, 0}}, {"light", {0.5, 0.5, 0.5}, {10, 10, 10}}};
  const double w = 4, h = 2, d = 2;
  // Room [0,4]×[0,2]×[0,2], faces inwards; each face one polygon spanning both halves.
  s.polygons = {quad({0, 0, 0}, {0, 0, d}, {w, 0, d}, {w, 0, 0}),   // floor (+y)
                quad({0, h, 0}, {w, h, 0}, {w, h, d}, {0, h, d}),   // ceiling (−y)
                quad({0, 0, 0}, {w, 0, 0}, {w, h, 0}, {0, h, 0}),   // z = 0 (+z)
                quad({0, 0, d}, {0, h, d}, {w, h, d}, {w, 0, d}),   // z = d (−z)
                quad({0, 0, 0}, {0, h, 0}, {0, h, d}, {0, 0, d}),   // x = 0 (+x)
                quad({w, 0, 0}, {w, 0, d}, {w, h, d}, {w, h, 0}),   // x = w (−x)
                // The dividing wall at x = 2, one face to each side.
                quad({2, 0, 0}, {2, 0, d}, {2, h, d}, {2, h, 0}),   // faces −x (lit side)
                quad({2, 0, 0}, {2, h, 0}, {2, h, d}, {2, 0, d}),   // faces +x (dark side)
                // The light, just under the ceiling on the left.
                quad({0.8, h - 0.01, 0.8}, {1.2, h - 0.01, 0.8}, {1.2, h - 0.01, 1.2}, {0.8, h - 0.01, 1.2}, 1)};
  ContactSplitStats split;
  const Scene scene = split_contacts(s, split);
  EXPECT_GE(split.polygons_split, 4u);  // floor, ceiling and the two long walls are cut at x = 2

  const Subdivision sub = subdivide_uniform(scene, 0.25);
  const RayScene rays(scene);
  const ClusterTree tree = build_cluster_tree(scene);
  FormFactorCounts counts;
  FormFactorSettings settings;
  settings.rays_per_point = 4;
  const FormFactorMatrix f = compute_form_factors(sub, &rays, &tree, settings, counts);
  std::vector<Vec3> rho, e;
  for (const Element& el : sub.elements) {
    rho.push_back(scene.materials[el.shape.material].reflectance);
    e.push_back(scene.materials[el.shape.material].emission);
  }
  SolveStats stats;
  const std::vector<Vec3> b = solve_gauss_seidel(f, rho, e, {}, stats);
  double lit = 0, dark = 0;
  for (size_t i = 0; i < b.size(); ++i) {
    if (e[i].x > 0) continue;
    const Vec3 c = sub.elements[i].centroid;
    // The dividing wall's faces stand at x = 2: its −x face belongs to the lit side.
    if (c.x < 2 || (c.x == 2 && sub.elements[i].normal.x < 0)) lit = std::max(lit, b[i].x);
    else dark = std::max(dark, b[i].x);
  }
  EXPECT_GT(lit, 0.1);
  EXPECT_LT(dark, 1e-4 * lit) << "dark " << dark << " lit " << lit;
}

// Pairs whose shaft holds nothing cast no rays; their form factors equal the unoccluded ones.
TEST(ShaftCulling, UnobstructedPairsCastNoRays) {
  const Scene box6 = test::closed_box(1.0, {0.5, 0.5, 0.5}, {1, 1, 1});
  Scene scene = box6;
  // An occluder in one corner only: most pairs of the room's elements cannot see it in their shaft.
  scene.polygons.push_back(quad({0.1, 0.2, 0.1}, {0.1, 0.2, 0.2}, {0.2, 0.2, 0.2}, {0.2, 0.2, 0.1}));
  const Subdivision sub = subdivide_uniform(scene, 0.25);
  const RayScene rays(scene);
  const ClusterTree tree = build_cluster_tree(scene);
  FormFactorCounts culled, all;
  const FormFactorMatrix fc = compute_form_factors(sub, &rays, &tree, {}, culled);
  const FormFactorMatrix fa = compute_form_factors(sub, &rays, nullptr, {}, all);
  EXPECT_GT(culled.unoccluded, culled.pairs / 4);
  EXPECT_LT(culled.rays, all.rays);
  ASSERT_EQ(fc.rows(), fa.rows());
  // Culling only skips rays that would all have arrived.
  for (size_t i = 0; i < fc.rows(); ++i) EXPECT_NEAR(fc.row_sum(i), fa.row_sum(i), 0.05) << i;
}

// A wall modelled as two coincident polygons back to back (one faces each room): a ray meets the face
// that looks at it, whichever order the polygons come in and from either side.
TEST(RayScene, CoincidentBackToBackPolygonsShowTheirFrontFace) {
  for (int order = 0; order < 2; ++order) {
    Scene s;
    s.materials.push_back({"wall", {0.5, 0.5, 0.5}, {}});
    const Polygon facing_minus_x = test::quad({1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, 0);
    Polygon facing_plus_x = facing_minus_x;
    std::swap(facing_plus_x.v[1], facing_plus_x.v[3]);
    ASSERT_LT(polygon_normal(facing_minus_x).x, 0);
    ASSERT_GT(polygon_normal(facing_plus_x).x, 0);
    s.polygons = order == 0 ? std::vector<Polygon>{facing_minus_x, facing_plus_x}
                            : std::vector<Polygon>{facing_plus_x, facing_minus_x};
    const RayScene rays(s);
    for (double y : {0.1, 0.37, 0.5, 0.9}) {
      const RayScene::Hit from_left = rays.intersect({0, y, 0.4}, {1, 0.01, 0.02});
      ASSERT_TRUE(from_left.hit);
      EXPECT_LT(polygon_normal(s.polygons[from_left.polygon]).x, 0) << "order " << order << " y " << y;
      const RayScene::Hit from_right = rays.intersect({2, y, 0.6}, {-1, -0.01, 0.03});
      ASSERT_TRUE(from_right.hit);
      EXPECT_GT(polygon_normal(s.polygons[from_right.polygon]).x, 0) << "order " << order << " y " << y;
    }
  }
}

}  // namespace
}  // namespace walkrad
