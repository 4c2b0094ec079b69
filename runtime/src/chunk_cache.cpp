// ChunkCache (chunk_cache.h): a greedy plan (the most useful chunks that fit the budget), loads
// asked for in plan order with a few in flight, evictions only of chunks outside the plan.
#include "walkrad/runtime/chunk_cache.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <numeric>

#include "walkrad/formats/chunk.h"

namespace walkrad {

namespace {

// A triangle brings at most 3 vertices of positions and colours (3 + 3 floats) and 3 indices.
constexpr uint64_t kBoundBytesPerTriangle = 3 * 6 * sizeof(float) + 3 * sizeof(uint32_t);

// Chunk indices, most useful first; ties in chunk order so that plans are deterministic.
std::vector<uint32_t> by_priority(const std::vector<double>& priority) {
  std::vector<uint32_t> order(priority.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return priority[a] > priority[b]; });
  return order;
}

}  // namespace

ChunkCache::ChunkCache(std::string bake_dir, const Manifest& manifest, const StreamSettings& settings)
    : budget_(settings.budget_bytes),
      // Enough to keep every worker busy while the render thread is between two updates; few enough
      // that a chunk that becomes urgent is asked for soon.
      max_in_flight_(size_t(std::max(settings.worker_threads, 1)) * 2),
      loader_(settings.worker_threads) {
  // The manifest reader has already refused chunk names that would leave the bake folder.
  for (const ChunkInfo& chunk : manifest.chunks) {
    Slot slot;
    slot.file = (std::filesystem::path(bake_dir) / chunk.file).string();
    slot.triangles = chunk.triangles;
    slots_.push_back(std::move(slot));
  }
}

ChunkCache::~ChunkCache() = default;

const GpuMesh* ChunkCache::mesh(uint32_t chunk) const {
  const Slot& slot = slots_.at(chunk);
  return slot.gpu ? &*slot.gpu : nullptr;
}

size_t ChunkCache::resident_count() const {
  return size_t(std::count_if(slots_.begin(), slots_.end(), [](const Slot& s) { return s.state == State::kResident; }));
}

uint64_t ChunkCache::estimate(const Slot& slot) const {
  return slot.bytes_known ? slot.bytes : slot.triangles * kBoundBytesPerTriangle;
}

uint64_t ChunkCache::room() const {
  if (budget_ == 0) return std::numeric_limits<uint64_t>::max();
  return budget_ > resident_bytes_ ? budget_ - resident_bytes_ : 0;
}

void ChunkCache::add_bytes(uint64_t bytes) {
  resident_bytes_ += bytes;
  max_resident_bytes_ = std::max(max_resident_bytes_, resident_bytes_);
}

void ChunkCache::ask(uint32_t chunk) {
  Slot& slot = slots_[chunk];
  slot.reserved = estimate(slot);
  add_bytes(slot.reserved);
  slot.state = State::kLoading;
  ++in_flight_;
  loader_.request(chunk, slot.file);
}

void ChunkCache::evict(uint32_t chunk) {
  Slot& slot = slots_[chunk];
  slot.gpu.reset();
  slot.state = State::kAbsent;
  resident_bytes_ -= slot.bytes;
  ++evictions_;
}

bool ChunkCache::make_room(uint64_t bytes, const std::vector<bool>& keep, const std::vector<double>& priority) {
  if (room() >= bytes) return true;
  std::vector<uint32_t> victims;
  for (uint32_t c = 0; c < slots_.size(); ++c)
    if (slots_[c].state == State::kResident && !keep[c]) victims.push_back(c);
  // Least useful first; among equals the later chunk, the mirror of by_priority's order.
  std::sort(victims.begin(), victims.end(), [&](uint32_t a, uint32_t b) {
    return priority[a] != priority[b] ? priority[a] < priority[b] : a > b;
  });
  uint64_t freeable = 0;
  for (uint32_t c : victims) freeable += slots_[c].bytes;
  if (room() + freeable < bytes && budget_ != 0) return false;  // evicting would not be enough: keep them
  for (uint32_t c : victims) {
    if (room() >= bytes) break;
    evict(c);
  }
  return room() >= bytes;
}

void ChunkCache::arrive(std::vector<LoadedChunk> loaded, const std::vector<double>& priority) {
  for (LoadedChunk& item : loaded) {
    Slot& slot = slots_[item.chunk];
    --in_flight_;
    resident_bytes_ -= slot.reserved;
    slot.reserved = 0;
    slot.state = State::kAbsent;
    if (item.error) std::rethrow_exception(item.error);
    slot.bytes = display_bytes(item.mesh);
    slot.bytes_known = true;
    bytes_loaded_ += item.file_bytes;
    ++loads_;
    // Only a mesh with unused vertices can outgrow its reservation; it comes in only if room is made.
    std::vector<bool> keep(slots_.size(), false);
    keep[item.chunk] = true;
    for (uint32_t c = 0; c < slots_.size(); ++c) keep[c] = keep[c] || priority[c] >= priority[item.chunk];
    if (!make_room(slot.bytes, keep, priority)) continue;
    slot.gpu.emplace(item.mesh);  // the upload, on the render thread; the CPU copy dies with `item`
    slot.state = State::kResident;
    add_bytes(slot.bytes);
  }
}

void ChunkCache::update(const std::vector<double>& priority) {
  arrive(loader_.take_finished(), priority);

  // The plan: the most useful chunks whose bytes fit the budget together.
  std::vector<bool> planned(slots_.size(), false);
  std::vector<uint32_t> to_ask;
  uint64_t planned_bytes = 0;
  for (uint32_t c : by_priority(priority)) {
    const uint64_t bytes = estimate(slots_[c]);
    if (budget_ != 0 && planned_bytes + bytes > budget_) continue;
    planned[c] = true;
    planned_bytes += bytes;
    if (slots_[c].state == State::kAbsent) to_ask.push_back(c);
  }
  for (uint32_t c : to_ask) {
    if (in_flight_ >= max_in_flight_) break;
    if (!make_room(estimate(slots_[c]), planned, priority)) break;  // wait for room rather than jump the queue
    ask(c);
  }
}

size_t ChunkCache::wait_for(const std::vector<uint32_t>& chunks, const std::vector<double>& priority) {
  // The waited-for chunks outrank every other: arrivals make room for them, never the reverse.
  std::vector<double> boosted = priority;
  const double top = priority.empty() ? 0.0 : *std::max_element(priority.begin(), priority.end());
  std::vector<bool> keep(slots_.size(), false);
  for (uint32_t c : chunks) {
    keep[c] = true;
    boosted[c] += top + 1.0;
  }
  std::vector<uint32_t> order = chunks;
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return boosted[a] > boosted[b]; });
  std::vector<bool> asked(slots_.size(), false);  // each at most once, so that the wait ends
  const auto any = [&](auto test) { return std::any_of(order.begin(), order.end(), test); };
  for (;;) {
    for (uint32_t c : order)
      if (slots_[c].state == State::kAbsent && !asked[c] && make_room(estimate(slots_[c]), keep, boosted)) {
        ask(c);
        asked[c] = true;
      }
    const bool loading = any([&](uint32_t c) { return slots_[c].state == State::kLoading; });
    // A chunk that found no room yet may find it once the loads under way land and become evictable.
    const bool blocked = any([&](uint32_t c) { return slots_[c].state == State::kAbsent && !asked[c]; });
    if (!loading && !(blocked && in_flight_ > 0)) break;
    arrive(loader_.wait_finished(), boosted);
  }
  return size_t(std::count_if(order.begin(), order.end(), [&](uint32_t c) { return slots_[c].state != State::kResident; }));
}

}  // namespace walkrad
