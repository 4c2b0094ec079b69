#include "walkrad/accuracy/reference_tracer.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

namespace walkrad {

namespace {

// A point uniform by area on a convex polygon: a triangle by the square-root warp (Turk 1990), a quad
// as its two triangles (v0 v1 v2, v0 v2 v3) chosen by area. `u` picks the triangle and is reused.
Vec3 uniform_point(const Polygon& p, double u, double v) {
  Vec3 a = p.v[0], b = p.v[1], c = p.v[2];
  if (p.count == 4) {
    const double a1 = length(cross(p.v[1] - p.v[0], p.v[2] - p.v[0]));
    const double a2 = length(cross(p.v[2] - p.v[0], p.v[3] - p.v[0]));
    const double split = a1 / std::max(a1 + a2, 1e-300);
    if (u < split) {
      u /= split;
    } else {
      u = (u - split) / std::max(1 - split, 1e-300);
      b = p.v[2];
      c = p.v[3];
    }
  }
  const double su = std::sqrt(std::min(u, 1.0));
  return a * (1 - su) + b * (su * (1 - v)) + c * (su * v);
}

// A direction about unit n with pdf cos θ / π (Malley's method), in the frame of Duff et al. 2017
// ("Building an orthonormal basis, revisited").
Vec3 cosine_direction(const Vec3& n, double u1, double u2) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
  const Vec3 t(1 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const Vec3 s(b, sign + n.y * n.y * a, -n.y);
  const double r = std::sqrt(u1), phi = 2 * kPi * u2;
  return normalize(t * (r * std::cos(phi)) + s * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - u1)));
}

// Veach's power heuristic (β = 2) for one sample of technique f against technique g (pdfs in solid angle).
double power_heuristic(double f, double g) { return f * f / (f * f + g * g); }

// A punctual light's intensity towards unit direction `out` (from the light) at distance r, written
// from the KHR_lights_punctual and EXT_lights_ies texts (not from the solvers' punctual_lights.h): a spot's angular
// attenuation is clamp(cd · scale + offset, 0, 1)², scale = 1 / max(0.001, cos inner − cos outer),
// offset = −cos outer · scale, cd the cosine to its axis; the range's window clamp(1 − (r/range)⁴, 0, 1).
Vec3 punctual_intensity(const PunctualLight& l, const Vec3& out, double r) {
  double k = 1.0;
  if (l.type == PunctualLight::Type::spot) {
    const double scale = 1.0 / std::max(0.001, std::cos(l.inner_cone) - std::cos(l.outer_cone));
    const double a = std::clamp(dot(l.direction, out) * scale - std::cos(l.outer_cone) * scale, 0.0, 1.0);
    k = a * a;
  }
  // A luminaire (EXT_lights_ies): the profile's candela towards `out` in the node's frame (scene.h's
  // light_frame; ies.h interpolates the web).
  if (l.type == PunctualLight::Type::ies) k = l.profile ? l.profile->intensity(light_frame(l, out)) : 0.0;
  if (l.range > 0) k *= std::clamp(1.0 - std::pow(r / l.range, 4.0), 0.0, 1.0);
  return l.intensity * k;
}

}  // namespace

ReferenceTracer::ReferenceTracer(const Scene& scene, const RayScene& rays) : scene_(scene), rays_(rays) {
  normals_.reserve(scene.polygons.size());
  emitter_index_.assign(scene.polygons.size(), -1);
  double total = 0;
  for (uint32_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    normals_.push_back(polygon_normal(p));
    const Material& m = scene.materials[p.material];
    const double power = luminance(m.emission) * polygon_area(p);
    if (m.emits() && power > 0) {
      emitter_index_[i] = int32_t(emitters_.size());
      emitters_.push_back(i);
      emitter_area_.push_back(polygon_area(p));
      emitter_power_.push_back(power);
      emitter_centre_.push_back(polygon_centroid(p));
      total += power;
      emitter_cdf_.push_back(total);
    }
  }
  for (double& c : emitter_cdf_) c /= total;
  if (!emitter_cdf_.empty()) emitter_cdf_.back() = 1.0;
}

void ReferenceTracer::selection(const Vec3& x, const Vec3& n, Choice& choice) const {
  choice.cdf.clear();
  if (emitters_.size() > kSpatialEmitters) {
    choice.cdf = emitter_cdf_;
    return;
  }
  double total = 0;
  for (size_t k = 0; k < emitters_.size(); ++k) {
    const Polygon& e = scene_.polygons[emitters_[k]];
    bool facing = false, before = false;  // some corner in front of x; x in front of the emitter
    for (int c = 0; c < e.count && !facing; ++c) facing = dot(e.v[size_t(c)] - x, n) > 0;
    before = dot(x - e.v[0], normals_[emitters_[k]]) > 0;
    if (facing && before) {
      const Vec3 d = emitter_centre_[k] - x;
      total += emitter_power_[k] / (dot(d, d) + emitter_area_[k]);
    }
    choice.cdf.push_back(total);
  }
  if (!(total > 0)) {
    choice.cdf.clear();
    return;
  }
  for (double& c : choice.cdf) c /= total;
  choice.cdf.back() = 1.0;
}

// Next-event estimate of the irradiance that emitters send straight to x (normal n).
Vec3 ReferenceTracer::direct(const Vec3& x, const Vec3& n, const Choice& choice, Rng& rng, uint64_t& rays) const {
  const double u = rng.uniform();
  if (choice.cdf.empty()) return {};
  const size_t k = std::min(emitters_.size() - 1, size_t(std::upper_bound(choice.cdf.begin(), choice.cdf.end(), u) -
                                                         choice.cdf.begin()));
  const double pk = choice.of(k);
  const Polygon& e = scene_.polygons[emitters_[k]];
  const double u1 = rng.uniform(), u2 = rng.uniform();
  const Vec3 y = uniform_point(e, u1, u2);
  const Vec3& ny = normals_[emitters_[k]];
  const Vec3 d = y - x;
  const double r2 = dot(d, d);
  if (!(r2 > 0) || pk <= 0) return {};
  const Vec3 dir = d / std::sqrt(r2);
  const double cx = dot(n, dir), cy = -dot(ny, dir);
  if (cx <= 0 || cy <= 0) return {};
  ++rays;
  const double off = rays_.offset();
  if (rays_.occluded(x + n * off, y + ny * off)) return {};
  // E/π is the emitted radiance; y's pdf is pk / area, in solid angle pk / area · r² / cos θy.
  const double light_pdf = pk / emitter_area_[k] * r2 / cy;
  return mul(scene_.materials[e.material].emission, rays_.transmittance(x + n * off, y + ny * off)) *
         (cx / (kPi * light_pdf) * power_heuristic(light_pdf, cx / kPi));
}

// What leaves a surface on the side of normal n is ρ × the irradiance on that side, plus, for a material
// that transmits (diffusely: MGF td, glTF diffuse transmission), τ × the irradiance on the other: one
// of the two chosen by their luminance, the path's weight divided by the choice's probability. A
// material that does not transmit draws no number: its paths are what they were.
void ReferenceTracer::scatter(const Material& m, Vec3& n, Vec3& beta, Rng& rng) const {
  if (!m.transmits()) {
    beta = mul(beta, m.reflectance);
    return;
  }
  const double r = luminance(m.reflectance), t = luminance(m.transmittance);
  const double p = r + t > 0 ? r / (r + t) : 0.5;
  if (rng.uniform() < p) {
    beta = mul(beta, m.reflectance) / p;
  } else {
    beta = mul(beta, m.transmittance) / (1 - p);
    n = n * -1.0;
  }
}

// The irradiance the punctual lights give x (normal n): I cos θ / r² each, a shadow ray each. No sampling:
// a point light is a delta in direction, which no cosine-weighted ray can meet. A directional light's
// (KHR_lights_punctual: lux on a surface facing it, read as W/m²) arrives from a uniform disc of its
// angular diameter: one direction ω drawn uniformly over that cap, E⊥ (ω·n) if its ray leaves the scene
// (the disc's radiance E⊥ / Ω times Ω: the estimate's mean is E⊥ over the disc's mean of ω·n). The sky:
// one cosine-weighted direction ω, π L(ω) if its ray leaves the scene (pdf cos θ / π: the mean is
// ∫ L V cos θ dω); paths end where they leave, so no light is counted twice. Every ray that crosses
// clear glass (Scene::glass) carries the panes' transmittance (RayScene::transmittance).
Vec3 ReferenceTracer::punctual(const Vec3& x, const Vec3& n, Rng& rng, uint64_t& rays) const {
  Vec3 E;
  const double off = rays_.offset();
  for (const PunctualLight& l : scene_.lights) {
    if (l.type == PunctualLight::Type::sky) {
      if (!l.sky) continue;
      const double u1 = rng.uniform(), u2 = rng.uniform();
      const Vec3 w = cosine_direction(n, u1, u2);
      const Vec3 L = l.sky->at(w);
      if (max_component(L) <= 0) continue;
      ++rays;
      if (rays_.occluded(x + n * off, x + w * (2e6 * off))) continue;
      E += mul(mul(l.intensity, L), rays_.transmittance(x + n * off, x + w * (2e6 * off))) * kPi;
      continue;
    }
    if (l.type == PunctualLight::Type::directional) {
      const double u1 = rng.uniform(), u2 = rng.uniform();
      const Vec3 w = cap_direction(-l.direction, l.angular_diameter / 2, u1, u2);
      const double c = dot(n, w);
      if (c <= 0) continue;
      ++rays;
      if (rays_.occluded(x + n * off, x + w * (2e6 * off))) continue;  // 2·10⁶ offsets: twice the diagonal
      E += mul(l.intensity, rays_.transmittance(x + n * off, x + w * (2e6 * off))) * c;
      continue;
    }
    const Vec3 d = l.position - x;
    const double r2 = dot(d, d);
    if (!(r2 > 0)) continue;
    const double r = std::sqrt(r2);
    const double c = dot(n, d) / r;
    if (c <= 0) continue;
    const Vec3 I = punctual_intensity(l, d * (-1.0 / r), r);
    if (max_component(I) <= 0) continue;
    ++rays;
    if (rays_.occluded(x + n * off, l.position)) continue;
    E += mul(I, rays_.transmittance(x + n * off, l.position)) * (c / r2);
  }
  return E;
}

double ReferenceTracer::light_pdf(const Choice& choice, uint32_t polygon, double r2, double cos_y) const {
  const int32_t k = emitter_index_[polygon];
  if (k < 0 || cos_y <= 0) return 0;
  return choice.of(size_t(k)) / emitter_area_[size_t(k)] * r2 / cos_y;
}

RadiosityEstimate ReferenceTracer::estimate(const SurfacePoint& point, int samples, uint64_t seed, uint64_t stream,
                                            uint64_t& rays) const {
  constexpr int kMaxBounces = 1000;  // a safety cap; Russian roulette ends paths long before
  Rng rng(seed, stream);
  const Material& m0 = scene_.materials[scene_.polygons[point.polygon].material];
  const double off = rays_.offset();
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, lum = 0, lum2 = 0;
  thread_local Choice choice;  // the emitters' chances at the path's current vertex
  for (int s = 0; s < samples; ++s) {
    Vec3 value = m0.emission;
    Vec3 beta{1, 1, 1};  // multiplies the irradiance at the current point
    Vec3 x = point.position, n = normals_[point.polygon];
    scatter(m0, n, beta, rng);
    for (int bounce = 0; bounce < kMaxBounces && max_component(beta) > 0; ++bounce) {
      selection(x, n, choice);
      value += mul(beta, direct(x, n, choice, rng, rays) + punctual(x, n, rng, rays));
      const double u1 = rng.uniform(), u2 = rng.uniform();
      const Vec3 dir = cosine_direction(n, u1, u2);
      ++rays;
      const RayScene::Hit hit = rays_.intersect(x + n * off, dir);
      if (!hit.hit) break;
      beta = mul(beta, rays_.transmittance(x + n * off, hit.position));  // clear glass on the way
      const Vec3& nq = normals_[hit.polygon];
      const Material& mq = scene_.materials[scene_.polygons[hit.polygon].material];
      const bool back = dot(nq, dir) >= 0;
      if (back && !mq.transmits()) break;  // a back face: opaque and black (a transmitting one has two sides)
      // The cosine-weighted estimate of H is B(y): its emitted part, weighted against next-event
      // estimation (which would have drawn y with light_pdf), then its reflected part, recursively.
      if (!back && mq.emits()) {
        const Vec3 d = hit.position - x;
        const double cos_x = dot(n, dir);
        value += mul(beta, mq.emission) * power_heuristic(cos_x / kPi, light_pdf(choice, hit.polygon, dot(d, d), -dot(nq, dir)));
      }
      Vec3 side = back ? nq * -1.0 : nq;  // the side the ray arrives on
      scatter(mq, side, beta, rng);
      if (bounce >= 2) {
        const double survive = std::min(0.95, max_component(beta));
        if (rng.uniform() >= survive) break;
        beta = beta / survive;
      }
      x = hit.position;
      n = side;
    }
    for (int c = 0; c < 3; ++c) {
      sum[c] += value[c];
      sum2[c] += value[c] * value[c];
    }
    const double l = luminance(value);
    lum += l;
    lum2 += l * l;
  }
  RadiosityEstimate r;
  r.samples = uint32_t(samples);
  const double n = std::max(1, samples);
  auto error = [n](double s1, double s2) {
    const double mean = s1 / n;
    const double var = n > 1 ? std::max(0.0, (s2 - n * mean * mean) / (n - 1)) : 0.0;
    return std::sqrt(var / n);
  };
  for (int c = 0; c < 3; ++c) {
    r.B[c] = sum[c] / n;
    r.standard_error[c] = error(sum[c], sum2[c]);
  }
  r.luminance_error = error(lum, lum2);
  return r;
}

std::vector<RadiosityEstimate> ReferenceTracer::estimate(const std::vector<SurfacePoint>& points,
                                                         const ReferenceSettings& settings, uint64_t& rays) const {
  std::vector<RadiosityEstimate> out(points.size());
  std::vector<uint64_t> counts(points.size(), 0);
  tbb::parallel_for(size_t(0), points.size(), [&](size_t k) {
    out[k] = estimate(points[k], settings.samples, settings.seed, k, counts[k]);
  });
  for (uint64_t c : counts) rays += c;
  return out;
}

}  // namespace walkrad
