// Playback: which viewpoint of a walkthrough the window shows now. Advances at a fixed frame rate
// (a walkthrough is a list of frames, not timed keyframes), loops at the end, pauses and steps.
// Plain state without GL, so that the controls can be tested on their own.
#pragma once

#include <cstddef>

namespace walkrad {

class Playback {
 public:
  // frame_count >= 1 and frames_per_second > 0.
  Playback(size_t frame_count, double frames_per_second);

  // Moves on by the frames that `seconds` of wall time hold; nothing while paused.
  void advance(double seconds);
  // Pauses and moves by `delta` frames (negative: back), wrapping around the ends.
  void step(int delta);
  void toggle_pause() { paused_ = !paused_; }

  size_t frame() const { return frame_; }
  bool paused() const { return paused_; }

 private:
  size_t frame_count_;
  double seconds_per_frame_;
  double pending_seconds_ = 0;  // wall time not yet turned into a whole frame
  size_t frame_ = 0;
  bool paused_ = false;
};

}  // namespace walkrad
