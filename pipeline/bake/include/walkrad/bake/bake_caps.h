// Caps on a bake's time and memory (walkrad bake --max-seconds, --max-memory-mb; README.md). They
// are checked at safe points — each phase's start and the end of each solve round (and during the
// classic method's form factors) — so a bake may run past a cap by one round at most. A cap reached
// throws InputError with kExitLimitReached; the staged output is then discarded and a previous
// output is left as it was.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace walkrad {

struct BakeCaps {
  double max_seconds = 0;      // wall-clock seconds since the bake began; 0: no cap
  uint64_t max_memory_mb = 0;  // peak resident memory (VmHWM) in MiB; 0: no cap
};

// Peak resident memory of this process in MiB (Linux /proc/self/status VmHWM; 0 where unknown).
uint64_t peak_memory_mb();

class CapWatch {
 public:
  CapWatch(BakeCaps caps, std::string scene);
  // Throws InputError(scene, where, …, kExitLimitReached) when a cap is reached.
  void check(const std::string& where) const;

 private:
  BakeCaps caps_;
  std::string scene_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace walkrad
