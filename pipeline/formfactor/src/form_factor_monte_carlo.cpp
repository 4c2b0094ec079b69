// Monte Carlo form factors by area sampling of both polygons (form_factor_monte_carlo.h).
#include "walkrad/formfactor/form_factor_monte_carlo.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "walkrad/formfactor/form_factor.h"
#include "walkrad/core/sampling.h"

namespace walkrad {

namespace {


// Samples per random stream: the streams, not the threads, fix which sample gets which numbers.
constexpr uint64_t kChunk = 4096;

// dA / (du dv) of sample_polygon at (u, v). A triangle's square-root warp is uniform (the area);
// a quad's bilinear map is uniform only for a parallelogram, so a trapezoid's samples are weighted
// by their Jacobian to stay unbiased.
double sample_jacobian(const Polygon& p, double area, double u, double v) {
  if (p.count == 3) return area;
  const Vec3 du = (p.v[1] - p.v[0]) * (1 - v) + (p.v[2] - p.v[3]) * v;
  const Vec3 dv = (p.v[3] - p.v[0]) * (1 - u) + (p.v[2] - p.v[1]) * u;
  return length(cross(du, dv));
}

// Running mean and sum of squared deviations (Welford 1962); merged by Chan et al. (1979).
struct Moments {
  uint64_t n = 0;
  double mean = 0, m2 = 0;
  void add(double x) {
    ++n;
    const double d = x - mean;
    mean += d / double(n);
    m2 += d * (x - mean);
  }
  void merge(const Moments& o) {
    if (o.n == 0) return;
    const double total = double(n + o.n), d = o.mean - mean;
    mean += d * double(o.n) / total;
    m2 += o.m2 + d * d * double(n) * double(o.n) / total;
    n += o.n;
  }
};

// Both estimators: plain area sampling of the kernel, or (control_variate) the exact unoccluded
// point form factor minus the kernel's occluded part.
MonteCarloEstimate estimate(const Polygon& receiver, const Polygon& source, const RayScene* occluders,
                            uint64_t samples, uint64_t seed, bool control_variate) {
  MonteCarloEstimate est;
  est.samples = samples;
  const double area_i = polygon_area(receiver), area_j = polygon_area(source);
  if (samples == 0 || !(area_i > 0) || !(area_j > 0)) return est;
  const Vec3 ni = polygon_normal(receiver), nj = polygon_normal(source);
  const double offset = occluders ? occluders->offset() : 0.0;

  const uint64_t chunks = (samples + kChunk - 1) / kChunk;
  std::vector<Moments> moments(chunks);
  tbb::parallel_for(uint64_t(0), chunks, [&](uint64_t c) {
    Rng rng(seed, c);
    Moments& m = moments[c];
    const uint64_t n = std::min(kChunk, samples - c * kChunk);
    for (uint64_t s = 0; s < n; ++s) {
      const double u0 = rng.uniform(), v0 = rng.uniform(), u1 = rng.uniform(), v1 = rng.uniform();
      const Vec3 x = sample_polygon(receiver, u0, v0), y = sample_polygon(source, u1, v1);
      const double weight_x = sample_jacobian(receiver, area_i, u0, v0) / area_i;  // 1 when uniform
      double f = 0.0;
      // point_to_polygon sees both sides of the source: behind its plane, x gets nothing.
      if (control_variate && dot(x - source.v[0], nj) > 0) f = point_to_polygon(x, ni, source);
      const Vec3 d = y - x;
      const double r2 = dot(d, d), cos_x = dot(ni, d), cos_y = -dot(nj, d);  // both times r
      if (r2 > 0 && cos_x > 0 && cos_y > 0 && (occluders || !control_variate)) {
        const double k = cos_x * cos_y / (kPi * r2 * r2) * sample_jacobian(source, area_j, u1, v1);
        // Only rays that would change the sample are cast.
        const bool blocked = occluders && occluders->occluded(x + ni * offset, y + nj * offset);
        if (control_variate) {
          if (blocked) f -= k;
        } else if (!blocked) {
          f = k;
        }
      }
      m.add(f * weight_x);
    }
  });
  Moments total;
  for (const Moments& m : moments) total.merge(m);  // in chunk order: independent of the threads
  est.value = total.mean;
  est.std_error = samples > 1 ? std::sqrt(total.m2 / double(samples - 1) / double(samples)) : 0.0;
  return est;
}

}  // namespace

MonteCarloEstimate form_factor_monte_carlo(const Polygon& receiver, const Polygon& source, const RayScene* occluders,
                                           uint64_t samples, uint64_t seed) {
  return estimate(receiver, source, occluders, samples, seed, false);
}

MonteCarloEstimate form_factor_monte_carlo_control_variate(const Polygon& receiver, const Polygon& source,
                                                           const RayScene* occluders, uint64_t samples,
                                                           uint64_t seed) {
  return estimate(receiver, source, occluders, samples, seed, true);
}

}  // namespace walkrad
