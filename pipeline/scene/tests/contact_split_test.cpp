// Contact splitting's smoothing groups and near-contact bands (contact_split.h): a piece under a
// cover or enclosed by what stands on it gets its own material; bands beside a cover's footprint, the
// outline grown by kContactBand gaps, on the pieces of the covered polygon around it, and nowhere else.
#include "walkrad/scene/contact_split.h"

#include <algorithm>
#include <cmath>
#include <string>

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

// Whether a floor piece (of a split scene) took the covered copy of its material.
bool covered(const Scene& split, const Polygon& piece) {
  return split.materials[piece.material].name.find("(covered)") != std::string::npos;
}

TEST(ContactSplit, PieceEnclosedByWhatStandsOnItTakesItsOwnMaterial) {
  // A box with no bottom face resting on the floor (a book on a shelf board): the floor under it is
  // enclosed by the four sides' backs; the floor around it faces their fronts.
  Scene s = box_over_floor(0.0);
  s.polygons.erase(std::remove_if(s.polygons.begin() + 1, s.polygons.end(),
                                  [](const Polygon& p) { return polygon_normal(p).y < -0.5; }),
                   s.polygons.end());
  ASSERT_EQ(s.polygons.size(), 6u);
  ContactSplitStats stats;
  const Scene split = split_contacts(s, stats);
  size_t under = 0, around = 0;
  for (const Polygon& q : split.polygons) {
    if (std::fabs(polygon_normal(q).y - 1) > 1e-9 || std::fabs(q.v[0].y) > 1e-12) continue;  // not the floor
    const Vec3 c = polygon_centroid(q);
    const bool inside = c.x > 2.3 && c.x < 2.9 && c.z > 1.7 && c.z < 2.3;
    EXPECT_EQ(covered(split, q), inside) << c.x << " " << c.z;
    (inside ? under : around) += 1;
  }
  EXPECT_EQ(under, 1u);
  EXPECT_EQ(around, 8u);  // the floor cut by the four sides' lines: 3 × 3 pieces
  EXPECT_EQ(stats.covered, 1u);
}

TEST(ContactSplit, NothingEnclosedWhereWhatStandsFacesBothWays) {
  // A wall across the floor as two one-sided quads back to back (x = 2, facing −x and +x): each side
  // of the floor is in front of one of them, so neither is enclosed. One quad alone leaves its back's
  // side enclosed (nothing there faces it).
  Scene s;
  s.materials.push_back({"grey", {0.5, 0.5, 0.5}, {0, 0, 0}});
  s.polygons.push_back(test::quad({0, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 0, 0}));  // faces +y
  Polygon wall = test::quad({2, 0, 0}, {2, 2, 0}, {2, 2, 4}, {2, 0, 4});
  if (polygon_normal(wall).x > 0) std::swap(wall.v[1], wall.v[3]);  // faces −x
  s.polygons.push_back(wall);
  Polygon back = wall;
  std::swap(back.v[1], back.v[3]);  // faces +x
  s.polygons.push_back(back);
  ContactSplitStats stats;
  const Scene both = split_contacts(s, stats);
  EXPECT_EQ(stats.covered, 0u);
  s.polygons.pop_back();
  ContactSplitStats one;
  const Scene single = split_contacts(s, one);
  EXPECT_EQ(one.covered, 1u);
  for (const Polygon& q : single.polygons)
    if (std::fabs(polygon_normal(q).y - 1) < 1e-9) {
      EXPECT_EQ(covered(single, q), polygon_centroid(q).x > 2) << polygon_centroid(q).x;
    }
}

}  // namespace
}  // namespace walkrad
