#include "walkrad/bake/bake_caps.h"

#include <cstdio>
#include <fstream>

#include "walkrad/formats/error.h"

namespace walkrad {

uint64_t peak_memory_mb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    unsigned long long kb = 0;
    if (std::sscanf(line.c_str(), "VmHWM: %llu kB", &kb) == 1) return kb / 1024;
  }
  return 0;
}

CapWatch::CapWatch(BakeCaps caps, std::string scene)
    : caps_(caps), scene_(std::move(scene)), start_(std::chrono::steady_clock::now()) {}

void CapWatch::check(const std::string& where) const {
  if (caps_.max_seconds > 0) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (seconds > caps_.max_seconds) {
      char text[160];
      std::snprintf(text, sizeof text, "the bake ran %.1f s, past --max-seconds %g: stopped, no output written", seconds,
                    caps_.max_seconds);
      throw InputError(scene_, where, text, kExitLimitReached);
    }
  }
  if (caps_.max_memory_mb > 0) {
    const uint64_t mb = peak_memory_mb();
    if (mb > caps_.max_memory_mb)
      throw InputError(scene_, where, "peak memory " + std::to_string(mb) + " MiB is past --max-memory-mb " +
                                          std::to_string(caps_.max_memory_mb) + ": stopped, no output written",
                       kExitLimitReached);
  }
}

}  // namespace walkrad
