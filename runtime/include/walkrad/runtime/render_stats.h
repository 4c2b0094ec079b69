// RenderStats: what the runtime measures about playing a bake — how long until the first frame,
// what each frame costs the CPU, what was streamed and what was missing. walkrad-view writes it as
// stats.json beside headless frames, so runtime performance can be tracked like the bake's own report.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

namespace walkrad {

struct RenderStats {
  double open_ms = 0;                  // manifest read, workers started
  double time_to_first_frame_ms = 0;   // from the start of open to the first frame finished on the GPU
  std::vector<double> frame_cpu_ms;    // CPU time of each frame (update + draw, waits included), in order
  uint64_t bytes_loaded = 0;           // chunk file bytes read from disk (again after an eviction)
  uint64_t chunk_loads = 0;            // chunks read and decoded
  uint64_t chunk_evictions = 0;        // chunks dropped to make room
  uint64_t chunk_misses = 0;           // chunks a frame needed that were not resident when it came (first frame excepted)
  uint64_t frames_with_misses = 0;
  size_t chunks_resident = 0;          // chunks on the GPU now
  size_t chunks_total = 0;             // chunks in the manifest
  uint64_t resident_bytes = 0;         // now (chunk_cache.h defines them)
  uint64_t max_resident_bytes = 0;     // the most at any time
  uint64_t budget_bytes = 0;           // 0: no limit
};

// {"open_ms", "time_to_first_frame_ms", "frames", "frame_cpu_ms": {"mean", "median", "p99", "max",
//  "each": [...]}, "bytes_loaded", "chunk_loads", "chunk_evictions", "chunk_misses",
//  "frames_with_misses", "chunks_resident", "chunks_total", "resident_bytes", "max_resident_bytes",
//  "budget_bytes"}
nlohmann::json stats_to_json(const RenderStats& stats);

// The q-quantile (0..1) of the values, nearest rank (the smallest value with at least q of them at
// or below it); 0 for none.
double quantile(std::vector<double> values, double q);

}  // namespace walkrad
