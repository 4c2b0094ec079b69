// FlyCamera (fly_camera.h): yaw/pitch angles to a forward vector, the usual first-person camera.
#include "walkrad/runtime/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace walkrad {

namespace {

Vec3 heading(double yaw) { return {std::sin(yaw), 0.0, -std::cos(yaw)}; }

}  // namespace

FlyCamera FlyCamera::from(const Viewpoint& view) {
  FlyCamera c;
  c.position = view.position;
  const Vec3 f = normalize(view.forward);
  c.pitch = std::clamp(std::asin(std::clamp(f.y, -1.0, 1.0)), -kMaxPitch, kMaxPitch);
  c.yaw = std::atan2(f.x, -f.z);
  c.yfov = view.yfov;
  c.aspect = view.aspect;
  return c;
}

Viewpoint FlyCamera::viewpoint() const {
  Viewpoint v;
  v.name = "free flight";
  v.position = position;
  v.forward = heading(yaw) * std::cos(pitch) + Vec3{0, std::sin(pitch), 0};
  const Vec3 right = normalize(cross(v.forward, Vec3{0, 1, 0}));
  v.up = cross(right, v.forward);
  v.yfov = yfov;
  v.aspect = aspect;
  return v;
}

void FlyCamera::turn(double yaw_by, double pitch_by) {
  yaw = std::remainder(yaw + yaw_by, 2.0 * kPi);
  pitch = std::clamp(pitch + pitch_by, -kMaxPitch, kMaxPitch);
}

void FlyCamera::move(double forward, double right, double up) {
  const Vec3 ahead = heading(yaw);
  const Vec3 side{std::cos(yaw), 0.0, std::sin(yaw)};  // ahead × +y
  position += ahead * forward + side * right + Vec3{0, up, 0};
}

}  // namespace walkrad
