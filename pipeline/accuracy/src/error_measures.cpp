#include "walkrad/accuracy/error_measures.h"

#include <algorithm>
#include <cmath>

namespace walkrad {

namespace {

double weight(const std::vector<double>& w, size_t i) { return w.empty() ? 1.0 : w[i]; }

// The measures of per-point differences d against reference values r (NaN in either: skipped).
ErrorMeasures measure(const std::vector<double>& d, const std::vector<double>& r, const std::vector<double>& w) {
  ErrorMeasures m;
  double d2 = 0, r2 = 0, wd2 = 0, wr2 = 0, rsum = 0, wsum = 0, wrsum = 0, wdsum = 0, dmax = 0;
  for (size_t i = 0; i < r.size(); ++i) {
    if (std::isnan(d[i]) || std::isnan(r[i])) continue;
    const double wi = weight(w, i);
    ++m.points;
    d2 += d[i] * d[i];
    r2 += r[i] * r[i];
    wd2 += wi * d[i] * d[i];
    wr2 += wi * r[i] * r[i];
    rsum += r[i];
    wsum += wi;
    wrsum += wi * r[i];
    wdsum += wi * d[i];
    dmax = std::max(dmax, std::fabs(d[i]));
  }
  if (m.points == 0) return m;
  const double wmean = wsum / double(m.points);
  double wdmax = 0;
  for (size_t i = 0; i < r.size(); ++i)
    if (!std::isnan(d[i]) && !std::isnan(r[i])) wdmax = std::max(wdmax, weight(w, i) / wmean * std::fabs(d[i]));
  m.rms = r2 > 0 ? std::sqrt(d2 / r2) : 0;
  m.rms_weighted = wr2 > 0 ? std::sqrt(wd2 / wr2) : 0;
  m.max = rsum > 0 ? dmax / (rsum / double(m.points)) : 0;
  m.max_weighted = wrsum > 0 ? wdmax / (wrsum / wsum) : 0;
  m.bias = wrsum > 0 ? wdsum / wrsum : 0;
  return m;
}

}  // namespace

ErrorMeasures relative_errors(const std::vector<double>& a, const std::vector<double>& reference,
                              const std::vector<double>& weights) {
  std::vector<double> d(a.size());
  for (size_t i = 0; i < a.size(); ++i) d[i] = a[i] - reference[i];
  return measure(d, reference, weights);
}

ErrorMeasures reference_error_bar(const std::vector<double>& reference, const std::vector<double>& standard_error,
                                  const std::vector<double>& weights) {
  std::vector<double> d(reference.size());
  for (size_t i = 0; i < reference.size(); ++i) d[i] = 1.96 * standard_error[i];
  return measure(d, reference, weights);
}

}  // namespace walkrad
