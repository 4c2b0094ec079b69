#include "walkrad/formfactor/punctual_lights.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "walkrad/core/sampling.h"
#include "walkrad/formfactor/sky_light.h"

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
  if (light.type == PunctualLight::Type::directional || light.type == PunctualLight::Type::sky) return {};  // the scene's
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

Vec3 directional_power(const PunctualLight& light, const std::vector<Polygon>& polygons) {
  double projected = 0;
  for (const Polygon& p : polygons) projected += polygon_area(p) * std::max(0.0, -dot(polygon_normal(p), light.direction));
  return light.intensity * projected;
}

namespace {

// What of the sun's disc reaches `from`, per channel: kSunRays rays towards a sunflower pattern of the
// disc (equal solid angles, the golden angle between neighbours), each to twice the scene's diagonal
// (2·10⁶ ray offsets, RayScene::offset): past the scene from any point in it; through clear glass, each
// ray's share times the panes' transmittance.
Vec3 sun_visibility(const PunctualLight& l, const Vec3& from, const RayScene& rays, uint64_t& rays_cast) {
  const Vec3 w = -l.direction;
  const double far = 2e6 * rays.offset();
  const auto seen = [&](const Vec3& d) {
    return rays.occluded(from, from + d * far) ? Vec3{} : rays.transmittance(from, from + d * far);
  };
  if (l.angular_diameter <= 0) {
    ++rays_cast;
    return seen(w);
  }
  constexpr double kGolden = 0.38196601125010515;  // (3 − √5) / 2 of a turn
  Vec3 open;
  for (int k = 0; k < kSunRays; ++k) {
    const double v = k * kGolden;
    open += seen(cap_direction(w, l.angular_diameter / 2, (k + 0.5) / kSunRays, v - std::floor(v)));
  }
  rays_cast += kSunRays;
  return open / double(kSunRays);
}

Vec3 irradiance(const Vec3& x, const Vec3& normal, const std::vector<PunctualLight>& lights, const RayScene* rays,
                uint64_t& rays_cast, const Vec3* origin, const SkyPattern& sky) {
  Vec3 e;
  for (const PunctualLight& l : lights) {
    if (l.type == PunctualLight::Type::sky) {
      if (l.sky)
        e += mul(l.intensity, sky_irradiance(*l.sky, normal, origin ? *origin : x + normal * (rays ? rays->offset() : 0.0), rays, sky,
                                             rays_cast));
      continue;
    }
    if (l.type == PunctualLight::Type::directional) {
      const double cosine = -dot(normal, l.direction);
      if (cosine <= 0) continue;
      const Vec3 seen = rays ? sun_visibility(l, origin ? *origin : x + normal * rays->offset(), *rays, rays_cast) : Vec3(1, 1, 1);
      e += mul(l.intensity, seen) * cosine;
      continue;
    }
    const Vec3 d = l.position - x;
    const double r2 = dot(d, d);
    if (!(r2 > 0)) continue;
    const double r = std::sqrt(r2);
    const Vec3 w = d / r;
    const double cosine = dot(normal, w);
    if (cosine <= 0) continue;
    const double falloff = light_distribution(l, -w) * range_window(l, r);
    if (falloff <= 0) continue;
    Vec3 through(1, 1, 1);
    if (rays) {
      ++rays_cast;
      const Vec3 from = origin ? *origin : x + normal * rays->offset();
      if (rays->occluded(from, l.position)) continue;
      through = rays->transmittance(from, l.position);
    }
    e += mul(l.intensity, through) * (cosine * falloff / r2);
  }
  return e;
}

}  // namespace

Vec3 point_irradiance(const Vec3& x, const Vec3& normal, const std::vector<PunctualLight>& lights, const RayScene* rays,
                      uint64_t& rays_cast, const Vec3* origin) {
  return irradiance(x, normal, lights, rays, rays_cast, origin, kSkyAtPoints);
}

std::vector<LightSpot> light_spots(const std::vector<PunctualLight>& lights, const Scene& scene, const RayScene& rays,
                                   int grid) {
  std::vector<LightSpot> out;
  const Bounds b = scene.bounds();
  const Vec3 centre = (b.lo + b.hi) * 0.5;
  const double radius = 0.5 * length(b.diagonal());
  if (!(radius > 0) || grid < 1) return out;
  for (const PunctualLight& l : lights) {
    if (l.type != PunctualLight::Type::directional || max_component(l.intensity) <= 0) continue;
    Vec3 t, s;
    frame(l.direction, t, s);
    const Vec3 start = centre - l.direction * (2 * radius);
    std::vector<std::vector<LightSpot>> rows(static_cast<size_t>(grid));
    tbb::parallel_for(0, grid, [&](int i) {
      const double v = radius * (2 * (i + 0.5) / grid - 1);
      for (int j = 0; j < grid; ++j) {
        const double u = radius * (2 * (j + 0.5) / grid - 1);
        if (u * u + v * v > radius * radius) continue;
        const RayScene::Hit hit = rays.intersect(start + t * u + s * v, l.direction);
        if (hit.hit && dot(polygon_normal(scene.polygons[hit.polygon]), l.direction) < 0)
          rows[size_t(i)].push_back({hit.polygon, hit.position});
      }
    });
    for (const std::vector<LightSpot>& row : rows) out.insert(out.end(), row.begin(), row.end());
  }
  return out;
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
      const Vec3 e = irradiance(x, normal, lights, rays, rays_cast, nullptr, kSkyOverElements);
      out.mean += e;
      lo = std::min(lo, luminance(e));
      hi = std::max(hi, luminance(e));
    }
  out.mean = out.mean / double(n * n);
  out.spread = hi - lo;
  return out;
}

}  // namespace walkrad
