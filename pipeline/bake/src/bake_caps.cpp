#include "walkrad/bake/bake_caps.h"

#include <algorithm>

#include <cstdint>
#include <cstdio>
#include <fstream>

#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

// A "Name: N kB" line of a /proc file, in MiB (0 where absent).
uint64_t proc_kb_field(const char* file, const char* format) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    unsigned long long kb = 0;
    if (std::sscanf(line.c_str(), format, &kb) == 1) return kb / 1024;
  }
  return 0;
}

}  // namespace

uint64_t peak_memory_mb() { return proc_kb_field("/proc/self/status", "VmHWM: %llu kB"); }

uint64_t resident_memory_mb() { return proc_kb_field("/proc/self/status", "VmRSS: %llu kB"); }

uint64_t machine_memory_mb() {
  uint64_t mb = proc_kb_field("/proc/meminfo", "MemTotal: %llu kB");
  std::ifstream cgroup("/sys/fs/cgroup/memory.max");  // cgroup v2; "max" when unlimited
  unsigned long long bytes = 0;
  if (cgroup >> bytes && bytes > 0 && (mb == 0 || bytes / (1024 * 1024) < mb)) mb = bytes / (1024 * 1024);
  return mb;
}

uint64_t default_memory_cap_mb() { return uint64_t(kDefaultMemoryShare * double(machine_memory_mb())); }

CapWatch::CapWatch(BakeCaps caps, std::string scene)
    : caps_(caps),
      memory_cap_mb_(caps.max_memory_mb == kDefaultMemoryCap ? default_memory_cap_mb() : caps.max_memory_mb),
      scene_(std::move(scene)),
      start_(std::chrono::steady_clock::now()) {}

std::string CapWatch::memory_cap_text() const {
  if (caps_.max_memory_mb != kDefaultMemoryCap) return "--max-memory-mb " + std::to_string(memory_cap_mb_);
  return "the memory cap of " + std::to_string(memory_cap_mb_) + " MiB (60% of this machine's " +
         std::to_string(machine_memory_mb()) + " MiB; --max-memory-mb sets another, 0 none)";
}

void CapWatch::check_predicted(const std::string& where, uint64_t predicted_mb, const std::string& what) const {
  if (memory_cap_mb_ == 0 || predicted_mb <= memory_cap_mb_) return;
  throw InputError(scene_, where,
                   what + " would need about " + std::to_string(predicted_mb) + " MiB, past " + memory_cap_text() +
                       ": stopped before it, no output written; ask for a coarser bake (a larger --error or a lower --quality, or a "
                       "larger --element-size) or allow more memory",
                   kExitLimitReached);
}

double CapWatch::seconds_left() const {
  if (caps_.max_seconds <= 0) return -1.0;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return std::max(0.0, caps_.max_seconds - seconds);
}

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
  if (memory_cap_mb_ > 0) {
    const uint64_t mb = peak_memory_mb();
    if (mb > memory_cap_mb_)
      throw InputError(scene_, where, "peak memory " + std::to_string(mb) + " MiB is past " + memory_cap_text() +
                                          ": stopped, no output written",
                       kExitLimitReached);
  }
}

}  // namespace walkrad
