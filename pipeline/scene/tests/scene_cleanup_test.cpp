// Duplicate polygons are dropped (and counted) before solving; the same corners facing the other
// way, or in another order, are handled as the same or another surface as they should be.
#include "walkrad/scene/scene_cleanup.h"

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

TEST(SceneCleanup, DropsCopiesKeepsBacksides) {
  Scene s = test::closed_box(1.0, {0.5, 0.5, 0.5}, {1, 1, 1});
  Polygon copy = s.polygons[0];
  std::rotate(copy.v.begin(), copy.v.begin() + 1, copy.v.begin() + 4);  // same quad, another first corner
  Polygon back = s.polygons[0];
  std::swap(back.v[1], back.v[3]);  // same corners, facing the other way: another surface
  s.polygons.push_back(copy);
  s.polygons.push_back(back);
  s.polygons.push_back(s.polygons[3]);
  EXPECT_EQ(remove_duplicate_polygons(s), 2u);
  ASSERT_EQ(s.polygons.size(), 7u);
  EXPECT_EQ(s.polygons.back().v, back.v);
  EXPECT_EQ(remove_duplicate_polygons(s), 0u);
}

}  // namespace
}  // namespace walkrad
