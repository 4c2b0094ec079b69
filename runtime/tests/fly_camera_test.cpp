// FlyCamera (fly_camera.h): round trip from a viewpoint, turning, moving level along the heading.
#include <cmath>

#include <gtest/gtest.h>

#include "walkrad/runtime/fly_camera.h"

namespace walkrad {
namespace {

void expect_near(const Vec3& a, const Vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-9);
  EXPECT_NEAR(a.y, b.y, 1e-9);
  EXPECT_NEAR(a.z, b.z, 1e-9);
}

TEST(FlyCamera, KeepsTheViewpointItStartsFrom) {
  Viewpoint v;
  v.position = {1, 2, 3};
  v.forward = normalize(Vec3{1, -1, 0});
  v.up = normalize(Vec3{1, 1, 0});
  v.yfov = 0.9;
  v.aspect = 1.5;
  const Viewpoint back = FlyCamera::from(v).viewpoint();
  expect_near(back.position, v.position);
  expect_near(back.forward, v.forward);
  expect_near(back.up, v.up);
  EXPECT_EQ(back.yfov, 0.9);
  EXPECT_EQ(back.aspect, 1.5);
}

TEST(FlyCamera, TurnsAndMovesLevelAlongItsHeading) {
  FlyCamera c;
  expect_near(c.viewpoint().forward, {0, 0, -1});
  c.turn(kPi / 2, 0);  // a quarter turn to the right: looking down +x
  expect_near(c.viewpoint().forward, {1, 0, 0});
  c.turn(0, 0.5);
  c.move(2, 1, 0.5);   // level 2 m along +x whatever the pitch, 1 m to the right (+z), 0.5 m up
  expect_near(c.position, {2, 0.5, 1});
  c.turn(0, 10);
  EXPECT_DOUBLE_EQ(c.pitch, FlyCamera::kMaxPitch);
  const Viewpoint v = c.viewpoint();
  EXPECT_NEAR(dot(v.forward, v.up), 0.0, 1e-9);
  EXPECT_NEAR(length(v.up), 1.0, 1e-9);
}

}  // namespace
}  // namespace walkrad
