// Near-contact bands (contact_split.h): beside a cover's footprint, the outline grown by kContactBand
// gaps, on the pieces of the covered polygon around it, and nowhere else.
#include "walkrad/scene/contact_split.h"

#include <cmath>

#include <gtest/gtest.h>

#include "walkrad/scene/cluster_tree.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

// A 4 m floor and a 0.6 m cube standing `gap` above it at x, z in [2.3, 2.9] × [1.7, 2.3].
Scene box_over_floor(double gap) {
  Scene s;
  s.materials.push_back({"grey", {0.5, 0.5, 0.5}, {0, 0, 0}});
  s.polygons.push_back(test::quad({0, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 0, 0}));  // faces +y
  test::add_cube(s, {2.6, gap + 0.3, 2.0}, 0.6);
  return s;
}

TEST(ContactBands, GrownFootprintOnTheCoveredPolygonsPieces) {
  const double gap = 0.002, w = kContactBand * gap;
  ContactSplitStats stats;
  const Scene split = split_contacts(box_over_floor(gap), stats);
  ASSERT_GT(stats.covered, 0u);
  std::vector<uint8_t> wanted(split.polygons.size(), 1);
  const auto bands = contact_bands(split, build_cluster_tree(split), wanted);
  ASSERT_EQ(bands.size(), split.polygons.size());
  // Every segment lies on the floor, on the outline of [2.3 − w, 2.9 + w] × [1.7 − w, 2.3 + w], and
  // inside the piece it was found for; together they cover that outline's length once.
  double length_sum = 0;
  size_t pieces_with_bands = 0;
  for (size_t p = 0; p < bands.size(); ++p) {
    const Polygon& q = split.polygons[p];
    const bool floor = std::fabs(polygon_normal(q).y - 1) < 1e-9 && std::fabs(q.v[0].y) < 1e-12;
    if (!floor) {
      EXPECT_TRUE(bands[p].empty()) << "polygon " << p << " (the box) is beside no cover's outline";
      continue;
    }
    const Bounds b = polygon_bounds(q);
    const bool under = b.lo.x >= 2.3 - 1e-9 && b.hi.x <= 2.9 + 1e-9 && b.lo.z >= 1.7 - 1e-9 && b.hi.z <= 2.3 + 1e-9;
    if (under) {
      EXPECT_TRUE(bands[p].empty()) << "the band lies outside the footprint";
    }
    pieces_with_bands += !bands[p].empty();
    for (const ContactBand& s : bands[p]) {
      for (const Vec3& v : {s.a, s.b}) {
        EXPECT_NEAR(v.y, 0.0, 1e-12);
        const bool on_x = std::fabs(v.x - (2.3 - w)) < 1e-9 || std::fabs(v.x - (2.9 + w)) < 1e-9;
        const bool on_z = std::fabs(v.z - (1.7 - w)) < 1e-9 || std::fabs(v.z - (2.3 + w)) < 1e-9;
        EXPECT_TRUE(on_x || on_z) << v.x << " " << v.z;
        EXPECT_TRUE(v.x >= b.lo.x - 1e-9 && v.x <= b.hi.x + 1e-9 && v.z >= b.lo.z - 1e-9 && v.z <= b.hi.z + 1e-9);
      }
      length_sum += length(s.b - s.a);
    }
  }
  EXPECT_GE(pieces_with_bands, 4u);
  EXPECT_NEAR(length_sum, 4 * (0.6 + 2 * w), 1e-9);
}

TEST(ContactBands, NoneWhereNothingCovers) {
  for (const double gap : {0.0, 0.05}) {  // resting on the floor; farther than a cover's gap (2% of 0.6 m)
    ContactSplitStats stats;
    const Scene split = split_contacts(box_over_floor(gap), stats);
    const auto bands = contact_bands(split, build_cluster_tree(split), std::vector<uint8_t>(split.polygons.size(), 1));
    for (const auto& b : bands) EXPECT_TRUE(b.empty()) << "gap " << gap;
  }
  // Nor on polygons not asked for.
  ContactSplitStats stats;
  const Scene split = split_contacts(box_over_floor(0.002), stats);
  for (const auto& b : contact_bands(split, build_cluster_tree(split), std::vector<uint8_t>(split.polygons.size(), 0))) EXPECT_TRUE(b.empty());
}

}  // namespace
}  // namespace walkrad
