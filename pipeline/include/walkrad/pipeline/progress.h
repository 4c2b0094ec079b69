// Progress on the terminal during long phases: "walkrad: form factors 42% (1.2 s, ~1.7 s left)",
// at most twice a second, from whichever worker thread gets there first.
#pragma once

#include <atomic>
#include <chrono>
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

}  // namespace walkrad
