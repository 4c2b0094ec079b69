// stats_to_json (render_stats.h): the per-frame list plus its mean and maximum, which are what a
// reader compares between runs.
#include "walkrad/runtime/render_stats.h"

#include <algorithm>
#include <numeric>

namespace walkrad {

nlohmann::json stats_to_json(const RenderStats& stats) {
  const auto& each = stats.frame_cpu_ms;
  const double mean = each.empty() ? 0.0 : std::accumulate(each.begin(), each.end(), 0.0) / double(each.size());
  const double max = each.empty() ? 0.0 : *std::max_element(each.begin(), each.end());
  return {{"open_ms", stats.open_ms},
          {"time_to_first_frame_ms", stats.time_to_first_frame_ms},
          {"frames", each.size()},
          {"frame_cpu_ms", {{"mean", mean}, {"max", max}, {"each", each}}},
          {"bytes_loaded", stats.bytes_loaded},
          {"chunks_resident", stats.chunks_resident},
          {"chunks_total", stats.chunks_total}};
}

}  // namespace walkrad
