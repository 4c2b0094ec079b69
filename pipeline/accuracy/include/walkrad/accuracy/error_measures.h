// Error measures of a bake against a reference over sample points (docs/accuracy.md): relative RMS
// and relative maximum, each plain and importance-weighted. Values are luminances of radiosity;
// points where either side is NaN (no hit, an emitter, a silhouette mismatch) are left out.
//   rms          = sqrt(Σ (a − r)² / Σ r²)
//   rms_weighted = sqrt(Σ w (a − r)² / Σ w r²)
//   max          = max |a − r| / mean(r)
//   max_weighted = max (w / mean(w)) |a − r| / (Σ w r / Σ w)
//   bias         = Σ w (a − r) / Σ w r   (signed: below 0, the bake is too dark on average)
#pragma once

#include <cstddef>
#include <vector>

namespace walkrad {

struct ErrorMeasures {
  double rms = 0, rms_weighted = 0, max = 0, max_weighted = 0, bias = 0;
  size_t points = 0;  // compared
};

// weights may be empty (all 1).
ErrorMeasures relative_errors(const std::vector<double>& a, const std::vector<double>& reference,
                              const std::vector<double>& weights = {});

// The reference's own error bar on the same scale: relative RMS of its 95% half-widths (1.96 σ),
// plain and weighted, over the points where reference is not NaN.
ErrorMeasures reference_error_bar(const std::vector<double>& reference, const std::vector<double>& standard_error,
                                  const std::vector<double>& weights = {});

}  // namespace walkrad
