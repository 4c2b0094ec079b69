// RenderStats: what the runtime measures about playing a bake — how long until the first frame,
// what each frame costs the CPU, what was loaded. walkrad-view writes it as stats.json beside
// headless frames, so runtime performance can be tracked like the bake's own report.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

namespace walkrad {

struct RenderStats {
  double open_ms = 0;                  // manifest read, chunks read, decoded and uploaded
  double time_to_first_frame_ms = 0;   // from the start of open to the first frame finished on the GPU
  std::vector<double> frame_cpu_ms;    // CPU time of each draw, in order
  uint64_t bytes_loaded = 0;           // chunk file bytes read from disk
  size_t chunks_resident = 0;          // chunks on the GPU now
  size_t chunks_total = 0;             // chunks in the manifest
};

// {"open_ms", "time_to_first_frame_ms", "frames", "frame_cpu_ms": {"mean", "max", "each": [...]},
//  "bytes_loaded", "chunks_resident", "chunks_total"}
nlohmann::json stats_to_json(const RenderStats& stats);

}  // namespace walkrad
