// Progress on the terminal during long phases: "walkrad: form factors 42% (1.2 s, ~1.7 s left)",
// at most twice a second, from whichever worker thread gets there first.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

namespace walkrad {

class Progress {
 public:
  Progress(std::string phase, size_t total, bool enabled);
  ~Progress();  // prints the phase's final line
  void update(size_t done);

 private:
  using Clock = std::chrono::steady_clock;
  std::string phase_;
  size_t total_;
  bool enabled_;
  Clock::time_point start_;
  std::atomic<int64_t> last_print_ms_{0};
  std::mutex print_;
};

// Time left in hierarchical refinement, estimated from its last two rounds: past its peak, the wave of
// new links shrinks about geometrically (ratio r = last / previous), so the rounds left add about
// last · r / (1 − r) links, at the last round's cost per link. Negative while still growing (unknown).
double refinement_seconds_left(uint64_t previous_new_links, uint64_t last_new_links, double last_round_seconds);

// An upper bound on the solve's time left while the wave of new links still grows (the estimate above
// unknown): a bake that does not end first stops at its memory cap, which memory growing at the solve's
// average rate so far, (now − start) / seconds, reaches in (cap − now) / rate. Negative where unknown
// (no cap, or no growth yet).
double seconds_to_memory_cap(uint64_t cap_mb, uint64_t start_mb, uint64_t now_mb, double seconds);

}  // namespace walkrad
