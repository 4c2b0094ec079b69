// A bake read back as a viewer sees it (BakeSampler), against the reference tracer's estimates at the
// same points: the relative RMS of luminance and the reference's own RMS standard error beside it.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "walkrad/accuracy/bake_sampler.h"
#include "walkrad/accuracy/reference_tracer.h"

namespace walkrad::test {

// The input polygon of `material` facing `normal` (unit) whose plane holds `point`, inside it: where
// the reference tracer is asked about that point.
inline uint32_t polygon_at(const Scene& s, const std::string& material, const Vec3& normal, const Vec3& point) {
  for (uint32_t k = 0; k < s.polygons.size(); ++k) {
    const Polygon& p = s.polygons[k];
    if (s.materials[p.material].name != material || dot(polygon_normal(p), normal) <= 0.999 ||
        std::fabs(dot(point - p.v[0], normal)) >= 1e-6)
      continue;
    bool inside = true;
    for (int e = 0; e < p.count && inside; ++e)
      inside = dot(cross(p.v[size_t((e + 1) % p.count)] - p.v[size_t(e)], point - p.v[size_t(e)]), normal) >= 0;
    if (inside) return k;
  }
  ADD_FAILURE() << "no " << material << " polygon there";
  return 0;
}

struct ReferenceComparison {
  double rms = 0;  // relative, luminance
  double bar = 0;  // the reference's standard error, relative, RMS over the points
};

// Point k is read along a ray from at[k] + up[k] × lift towards −up[k], which must meet the bake at
// `lift`. WALKRAD_TEST_VERBOSE prints each point.
inline ReferenceComparison compare_with_reference(const BakeSampler& sampler, const std::vector<SurfacePoint>& at,
                                                  const std::vector<Vec3>& up, double lift,
                                                  const std::vector<RadiosityEstimate>& ref) {
  double sq = 0, noise = 0;
  for (size_t k = 0; k < ref.size(); ++k) {
    const BakeSampler::Sample b = sampler.along(at[k].position + up[k] * lift, up[k] * -1.0);
    EXPECT_TRUE(b.hit && std::fabs(b.distance - lift) < 1e-2 * lift) << "point " << k;
    const double r = luminance(ref[k].B), e = (luminance(b.B) - r) / r;
    sq += e * e;
    noise += (ref[k].luminance_error / r) * (ref[k].luminance_error / r);
    if (std::getenv("WALKRAD_TEST_VERBOSE")) {
      const Vec3 x = at[k].position;
      std::printf("  (%.2f %.2f %.2f) bake %.4f reference %.4f ± %.4f (%+.1f%%)\n", x.x, x.y, x.z, luminance(b.B), r,
                  ref[k].luminance_error, 100 * e);
    }
  }
  const double n = double(std::max<size_t>(ref.size(), 1));
  return {std::sqrt(sq / n), std::sqrt(noise / n)};
}

// The same, the reference traced here with `samples` paths a point.
inline ReferenceComparison compare_with_reference(const ReferenceTracer& tracer, const BakeSampler& sampler,
                                                  const std::vector<SurfacePoint>& at, const std::vector<Vec3>& up,
                                                  double lift, int samples) {
  ReferenceSettings rs;
  rs.samples = samples;
  uint64_t cast = 0;
  return compare_with_reference(sampler, at, up, lift, tracer.estimate(at, rs, cast));
}

}  // namespace walkrad::test
