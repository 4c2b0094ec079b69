// The bake's own estimate of its error, as `walkrad sweep` measures error (relative RMS of luminance,
// each point weighed by the solid angle it covers; emitters left out): at every primary-ray hit of
// the walkthrough, the leaf's estimated error is the root sum square of the errors its own links and
// its ancestors' leave (HNode::error, measured by ErrorOracle::measure_left_error). Over the whole
// walkthrough and per stretch of it (its frames cut into at most kEstimateSegments consecutive
// segments). Without viewpoints, over the leaves by area.
#pragma once

#include <cstddef>
#include <vector>

#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad {

inline constexpr size_t kEstimateSegments = 8;

struct EstimatedError {
  struct Segment {
    size_t first_view = 0, last_view = 0;
    double error = 0;
  };
  double overall = 0;
  bool over_views = false;        // the walkthrough's hits; false: the surfaces by area
  std::vector<Segment> segments;  // over_views only
};

EstimatedError estimate_error(const Hierarchy& h, const std::vector<ViewHit>& hits, size_t view_count);

}  // namespace walkrad
