// FlyCamera: the free-flight camera of the window mode — a position, a heading (yaw about the
// world's +y, 0 looking down −z) and a pitch — turned into a Viewpoint for the player. Plain state
// without GL, so that its arithmetic can be tested on its own. Assumes +y up, as glTF does.
#pragma once

#include "walkrad/formats/scene.h"

namespace walkrad {

struct FlyCamera {
  Vec3 position;
  double yaw = 0;    // radians, positive turns from −z towards +x
  double pitch = 0;  // radians, positive looks up; kept within ±kMaxPitch
  double yfov = 0.8;
  double aspect = 1.0;

  static constexpr double kMaxPitch = 1.55;  // just under 90°: the view frame stays defined

  // The camera that looks like `view` (its roll is dropped).
  static FlyCamera from(const Viewpoint& view);
  Viewpoint viewpoint() const;
  void turn(double yaw_by, double pitch_by);
  // Moves along the heading (level, whatever the pitch), to its right, and along +y, in metres.
  void move(double forward, double right, double up);
};

}  // namespace walkrad
