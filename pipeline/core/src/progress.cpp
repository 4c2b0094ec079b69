#include "walkrad/core/progress.h"

namespace walkrad {

Progress::Progress(std::string phase, size_t total, bool enabled)
    : phase_(std::move(phase)), total_(total), enabled_(enabled), start_(Clock::now()) {}

Progress::~Progress() {
  if (!enabled_) return;
  const double s = std::chrono::duration<double>(Clock::now() - start_).count();
  std::fprintf(stderr, "walkrad: %s done (%.2f s)\n", phase_.c_str(), s);
}

void Progress::update(size_t done) {
  if (!enabled_ || total_ == 0) return;
  const auto now = Clock::now();
  const int64_t ms = std::chrono::duration_cast<std::chrono::milliseconds>(now - start_).count();
  int64_t last = last_print_ms_.load();
  if (ms - last < 500 || !last_print_ms_.compare_exchange_strong(last, ms)) return;
  std::lock_guard<std::mutex> lock(print_);
  const double s = ms / 1000.0, fraction = double(done) / double(total_);
  const double left = fraction > 0 ? s * (1 - fraction) / fraction : 0;
  std::fprintf(stderr, "walkrad: %s %3.0f%% (%.1f s, ~%.1f s left)\n", phase_.c_str(), 100 * fraction, s, left);
}

double refinement_seconds_left(uint64_t previous_new_links, uint64_t last_new_links, double last_round_seconds) {
  if (last_new_links == 0) return 0.0;
  if (previous_new_links == 0 || last_new_links >= previous_new_links) return -1.0;
  const double r = double(last_new_links) / double(previous_new_links);
  return last_round_seconds * r / (1 - r);  // (seconds per link) × (links left)
}

double seconds_to_memory_cap(uint64_t cap_mb, uint64_t start_mb, uint64_t now_mb, double seconds) {
  if (cap_mb == 0 || now_mb <= start_mb || seconds <= 0) return -1.0;
  if (now_mb >= cap_mb) return 0.0;
  return double(cap_mb - now_mb) * seconds / double(now_mb - start_mb);
}

}  // namespace walkrad
