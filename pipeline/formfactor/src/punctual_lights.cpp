#include "walkrad/formfactor/punctual_lights.h"

#include <algorithm>
#include <cmath>

#include "walkrad/core/sampling.h"

namespace walkrad {

double light_distribution(const PunctualLight& light, const Vec3& out) {
  if (light.type == PunctualLight::Type::ies) return light.profile ? light.profile->intensity(light_frame(light, out)) : 0.0;
  if (light.type != PunctualLight::Type::spot) return 1.0;
  // KHR_lights_punctual's reference: scale = 1 / max(0.001, cos inner − cos outer), offset = −cos outer · scale.
  const double scale = 1.0 / std::max(0.001, std::cos(light.inner_cone) - std::cos(light.outer_cone));
  const double t = std::clamp(dot(light.direction, out) * scale - std::cos(light.outer_cone) * scale, 0.0, 1.0);
  return t * t;
}

double range_window(const PunctualLight& light, double r) {
  if (light.range <= 0) return 1.0;
  const double q = r / light.range;
  return std::clamp(1.0 - q * q * q * q, 0.0, 1.0);
}

Vec3 punctual_power(const PunctualLight& light) {
  if (light.type == PunctualLight::Type::point) return light.intensity * (4 * kPi);
  if (light.type == PunctualLight::Type::ies) return light.profile ? light.intensity * light.profile->flux() : Vec3{};
  // ∫ spot dΩ = 2π ∫ spot d(cos θ) over cos θ ∈ [cos outer, 1]; the falloff depends on cos θ alone
  // (a clamped quadratic): midpoint rule, 4096 steps.
  constexpr int kSteps = 4096;
  const double c0 = std::cos(light.outer_cone);
  const double scale = 1.0 / std::max(0.001, std::cos(light.inner_cone) - c0);
  double sum = 0;
  for (int k = 0; k < kSteps; ++k) {
    const double c = c0 + (1 - c0) * (k + 0.5) / kSteps;
    const double t = std::clamp((c - c0) * scale, 0.0, 1.0);
    sum += t * t;
  }
  return light.intensity * (2 * kPi * (1 - c0) * sum / kSteps);
}

Vec3 point_irradiance(const Vec3& x, const Vec3& normal, const std::vector<PunctualLight>& lights, const RayScene* rays,
                      uint64_t& rays_cast, const Vec3* origin) {
  Vec3 e;
  for (const PunctualLight& l : lights) {
    const Vec3 d = l.position - x;
    const double r2 = dot(d, d);
    if (!(r2 > 0)) continue;
    const double r = std::sqrt(r2);
    const Vec3 w = d / r;
    const double cosine = dot(normal, w);
    if (cosine <= 0) continue;
    const double falloff = light_distribution(l, -w) * range_window(l, r);
    if (falloff <= 0) continue;
    if (rays) {
      ++rays_cast;
      if (rays->occluded(origin ? *origin : x + normal * rays->offset(), l.position)) continue;
    }
    e += l.intensity * (cosine * falloff / r2);
  }
  return e;
}

DirectIrradiance direct_irradiance(const Polygon& p, const std::vector<PunctualLight>& lights, const RayScene* rays, int n,
                                   uint64_t& rays_cast) {
  DirectIrradiance out;
  if (lights.empty() || n < 1) return out;
  const Vec3 normal = polygon_normal(p);
  double lo = INFINITY, hi = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3 x = sample_polygon(p, (i + 0.5) / n, (j + 0.5) / n);
      const Vec3 e = point_irradiance(x, normal, lights, rays, rays_cast);
      out.mean += e;
      lo = std::min(lo, luminance(e));
      hi = std::max(hi, luminance(e));
    }
  out.mean = out.mean / double(n * n);
  out.spread = hi - lo;
  return out;
}

}  // namespace walkrad
