// find_openings (openings.h): a window in a wall of four quads, a door cut from a wall's bottom edge, a
// hole in a roof; none in a closed box, nor where T-junctions leave cracks.
#include "walkrad/scene/openings.h"

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

double total_area(const Opening& o) {
  double a = 0;
  for (const Polygon& t : o.triangles) a += polygon_area(t);
  return a;
}

Bounds bounds_of(const Opening& o) {
  Bounds b;
  for (const Polygon& t : o.triangles)
    for (int k = 0; k < 3; ++k) b.extend(t.v[k]);
  return b;
}

TEST(Openings, AWindowInAWallOfFourQuads) {
  const std::vector<Opening> found = find_openings(test::window_room());
  ASSERT_EQ(found.size(), 1u);
  const Opening& w = found[0];
  EXPECT_NEAR(w.area, 2 * 1.2, 1e-7);
  EXPECT_NEAR(total_area(w), 2 * 1.2, 1e-7);
  const Bounds b = bounds_of(w);
  EXPECT_NEAR(b.lo.x, 6, 1e-7);
  EXPECT_NEAR(b.hi.x, 6, 1e-7);
  EXPECT_NEAR(b.lo.y, 2, 1e-7);
  EXPECT_NEAR(b.hi.y, 4, 1e-7);
  EXPECT_NEAR(b.lo.z, 1, 1e-7);
  EXPECT_NEAR(b.hi.z, 2.2, 1e-7);
  for (const Polygon& t : w.triangles) EXPECT_NEAR(std::fabs(dot(polygon_normal(t), w.normal)), 1, 1e-7);
}

// A door: the wall y = 0 as three quads around x ∈ [2, 3], z ∈ [0, 2]; seen from both faces (a wall of
// no thickness modelled twice, back to back), still one opening.
TEST(Openings, ADoorCutFromAWallsBottomEdge) {
  Scene s;
  s.materials.push_back({"wall", {0.5, 0.5, 0.5}, {}});
  for (int facing : {+1, -1}) {
    s.polygons.push_back(test::rect(1, 0, 0, 3, 0, 2, facing));   // spans z, x: x ∈ [0, 2]
    s.polygons.push_back(test::rect(1, 0, 0, 3, 3, 6, facing));   // x ∈ [3, 6]
    s.polygons.push_back(test::rect(1, 0, 2, 3, 2, 3, facing));   // above the door
  }
  const std::vector<Opening> found = find_openings(s);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NEAR(found[0].area, 2, 1e-7);
  const Bounds b = bounds_of(found[0]);
  EXPECT_NEAR(b.lo.x, 2, 1e-7);
  EXPECT_NEAR(b.hi.x, 3, 1e-7);
  EXPECT_NEAR(b.lo.z, 0, 1e-7);
  EXPECT_NEAR(b.hi.z, 2, 1e-7);
}

// A closed box has none; a floor cut into quads that meet at T-junctions, none; an L of two quads, the
// corner of its hull (not an opening to anything, but found as one).
TEST(Openings, NoneInAClosedBoxNorAtTJunctions) {
  EXPECT_TRUE(find_openings(test::closed_box(2, {0.5, 0.5, 0.5}, {})).empty());
  Scene floor;
  floor.materials.push_back({"floor", {0.5, 0.5, 0.5}, {}});
  floor.polygons.push_back(test::rect(2, 0, 0, 2, 0, 4, +1));
  floor.polygons.push_back(test::rect(2, 0, 2, 4, 0, 1, +1));
  floor.polygons.push_back(test::rect(2, 0, 2, 4, 1, 2.5, +1));
  floor.polygons.push_back(test::rect(2, 0, 2, 4, 2.5, 4, +1));
  EXPECT_TRUE(find_openings(floor).empty());
  Scene l;
  l.materials = floor.materials;
  l.polygons.push_back(test::rect(2, 0, 0, 2, 0, 4, +1));
  l.polygons.push_back(test::rect(2, 0, 2, 4, 0, 2, +1));
  const std::vector<Opening> found = find_openings(l);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NEAR(found[0].area, 2, 1e-7);  // the triangle (2, 2) (4, 2) (2, 4)
}

}  // namespace
}  // namespace walkrad
