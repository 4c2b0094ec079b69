// RenderStats (render_stats.h): the per-frame list plus its mean, median, 99th percentile and
// maximum, which are what a reader compares between runs.
#include "walkrad/runtime/render_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace walkrad {

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const size_t rank = size_t(std::max(1.0, std::ceil(q * double(values.size()))));
  std::nth_element(values.begin(), values.begin() + long(rank - 1), values.end());
  return values[rank - 1];
}

nlohmann::json stats_to_json(const RenderStats& stats) {
  const auto& each = stats.frame_cpu_ms;
  const double mean = each.empty() ? 0.0 : std::accumulate(each.begin(), each.end(), 0.0) / double(each.size());
  const double max = each.empty() ? 0.0 : *std::max_element(each.begin(), each.end());
  return {{"open_ms", stats.open_ms},
          {"time_to_first_frame_ms", stats.time_to_first_frame_ms},
          {"frames", each.size()},
          {"frame_cpu_ms",
           {{"mean", mean}, {"median", quantile(each, 0.5)}, {"p99", quantile(each, 0.99)}, {"max", max},
            {"each", each}}},
          {"bytes_loaded", stats.bytes_loaded},
          {"chunk_loads", stats.chunk_loads},
          {"chunk_evictions", stats.chunk_evictions},
          {"chunk_misses", stats.chunk_misses},
          {"frames_with_misses", stats.frames_with_misses},
          {"chunks_resident", stats.chunks_resident},
          {"chunks_total", stats.chunks_total},
          {"resident_bytes", stats.resident_bytes},
          {"max_resident_bytes", stats.max_resident_bytes},
          {"budget_bytes", stats.budget_bytes}};
}

}  // namespace walkrad
