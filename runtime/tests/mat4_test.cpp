// The camera maths against hand-computed cases: a wrong sign here mirrors or empties every frame.
#include <cmath>

#include <gtest/gtest.h>

#include "walkrad/runtime/camera.h"
#include "walkrad/runtime/mat4.h"

namespace walkrad {
namespace {


TEST(Mat4, IdentityIsNeutral) {
  Mat4 a = Mat4::identity();
  a.at(0, 3) = 5.0f;
  a.at(2, 1) = -2.0f;
  EXPECT_EQ((a * Mat4::identity()).m, a.m);
  EXPECT_EQ((Mat4::identity() * a).m, a.m);
}

// The Cornell box camera (docs: cornell-box.md) looks along +z with y up, so its right is −x:
// the red wall (x ≈ 0.556 m) must come out on the left.
TEST(Mat4, ViewMatrixPutsForwardOnMinusZAndRightOnPlusX) {
  const Vec3 eye{0.278, 0.273, -0.8}, forward{0, 0, 1}, up{0, 1, 0};
  const Mat4 view = view_matrix(eye, forward, up);
  const auto ahead = view.transform(0.278f, 0.273f, -0.8f + 2.0f, 1.0f);
  EXPECT_NEAR(ahead[0], 0.0f, 1e-6);
  EXPECT_NEAR(ahead[1], 0.0f, 1e-6);
  EXPECT_NEAR(ahead[2], -2.0f, 1e-6);
  const auto red_wall = view.transform(0.556f, 0.273f, 0.0f, 1.0f);
  EXPECT_LT(red_wall[0], 0.0f);
  const auto above = view.transform(0.278f, 1.273f, -0.8f, 1.0f);
  EXPECT_NEAR(above[1], 1.0f, 1e-6);
}

TEST(Mat4, PerspectiveMapsClipPlanesAndFieldOfView) {
  const double near = 0.1, far = 50.0, yfov = kPi / 2.0;
  const Mat4 p = perspective(yfov, 2.0, near, far);
  const auto at_near = p.transform(0.0f, 0.0f, float(-near), 1.0f);
  EXPECT_NEAR(at_near[2] / at_near[3], -1.0f, 1e-5);
  const auto at_far = p.transform(0.0f, 0.0f, float(-far), 1.0f);
  EXPECT_NEAR(at_far[2] / at_far[3], 1.0f, 1e-4);
  // With a 90° vertical field, y = distance is the top edge; x = 2 × distance the right edge (aspect 2).
  const auto corner = p.transform(6.0f, 3.0f, -3.0f, 1.0f);
  EXPECT_NEAR(corner[0] / corner[3], 1.0f, 1e-6);
  EXPECT_NEAR(corner[1] / corner[3], 1.0f, 1e-6);
}

TEST(Camera, ClipPlanesFollowTheSceneBounds) {
  Bounds unit;
  unit.extend(Vec3{0, 0, 0});
  unit.extend(Vec3{1, 1, 1});
  Viewpoint view;
  view.position = {0.5, 0.5, 3.5};  // 3 m from the centre
  const ClipPlanes c = clip_planes(view, unit);
  EXPECT_NEAR(c.near, 1e-3 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(c.far, 4.0 * std::sqrt(3.0) + 3.0, 1e-12);
}

TEST(Camera, EmptyBoundsStillGiveAValidDepthRange) {
  const ClipPlanes c = clip_planes(Viewpoint{}, Bounds{});
  EXPECT_GT(c.near, 0.0);
  EXPECT_GT(c.far, c.near);
}

}  // namespace
}  // namespace walkrad
