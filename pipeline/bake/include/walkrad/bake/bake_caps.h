// Caps on a bake's time and memory (walkrad bake --max-seconds, --max-memory-mb; README.md). They
// are checked at safe points — each phase's start and the end of each solve round (and during the
// classic method's form factors) — so a bake may run past a time cap by one round at most. Memory is
// capped by default (60% of the machine's) and predicted: a solve round that the last rounds' growth
// says would pass the cap is not started. A cap reached
// throws InputError with kExitLimitReached; the staged output is then discarded and a previous
// output is left as it was.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace walkrad {

// The default memory cap: this share of the machine's memory (machine_memory_mb), so that a bake
// whose settings ask for more than fits stops with a message instead of swapping or being killed.
inline constexpr double kDefaultMemoryShare = 0.6;
inline constexpr uint64_t kDefaultMemoryCap = UINT64_MAX;  // max_memory_mb: resolved to the share above

struct BakeCaps {
  double max_seconds = 0;                       // wall-clock seconds since the bake began; 0: no cap
  uint64_t max_memory_mb = kDefaultMemoryCap;   // resident memory in MiB; 0: no cap
};

// Peak resident memory of this process in MiB (Linux /proc/self/status VmHWM; 0 where unknown).
uint64_t peak_memory_mb();

// Resident memory of this process now, in MiB (VmRSS; 0 where unknown).
uint64_t resident_memory_mb();

// The memory this process may use: /proc/meminfo's MemTotal, or the cgroup's memory.max where that
// is smaller (a container); MiB, 0 where unknown.
uint64_t machine_memory_mb();

// kDefaultMemoryShare of machine_memory_mb() (0, no cap, where that is unknown).
uint64_t default_memory_cap_mb();

class CapWatch {
 public:
  CapWatch(BakeCaps caps, std::string scene);
  // Throws InputError(scene, where, …, kExitLimitReached) when a cap is reached.
  void check(const std::string& where) const;

  // Before work whose memory can be predicted (the next solve round, from the growth of the last):
  // throws as check() does when predicted_mb would pass the memory cap. what: the work, for the message.
  void check_predicted(const std::string& where, uint64_t predicted_mb, const std::string& what) const;

  uint64_t memory_cap_mb() const { return memory_cap_mb_; }  // resolved; 0: none
  double seconds_left() const;  // before --max-seconds stops the bake; negative: no time cap

 private:
  std::string memory_cap_text() const;  // the cap and where it comes from, for messages

  BakeCaps caps_;
  uint64_t memory_cap_mb_ = 0;
  std::string scene_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace walkrad
