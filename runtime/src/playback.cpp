// Playback (playback.h): frame index arithmetic modulo the walkthrough's length.
#include "walkrad/runtime/playback.h"

#include <cmath>

namespace walkrad {

Playback::Playback(size_t frame_count, double frames_per_second)
    : frame_count_(frame_count), seconds_per_frame_(1.0 / frames_per_second) {}

void Playback::advance(double seconds) {
  if (paused_) return;
  pending_seconds_ += seconds;
  const double frames = std::floor(pending_seconds_ / seconds_per_frame_);
  pending_seconds_ -= frames * seconds_per_frame_;
  frame_ = (frame_ + size_t(frames)) % frame_count_;
}

void Playback::step(int delta) {
  paused_ = true;
  pending_seconds_ = 0;
  const long long n = static_cast<long long>(frame_count_);
  frame_ = size_t(((static_cast<long long>(frame_) + delta) % n + n) % n);
}

}  // namespace walkrad
