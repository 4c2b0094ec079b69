// sky_irradiance (sky_light.h): the cosine-weighted square cut adaptively where what the point sees of
// the sky changes.
#include "walkrad/formfactor/sky_light.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "walkrad/core/sampling.h"
#include "walkrad/formfactor/form_factor.h"

namespace walkrad {

namespace {

Vec3 direction(const Vec3& n, const Vec3& t, const Vec3& s, double a, double b) {
  const double r = std::sqrt(a), phi = 2 * kPi * b;
  return t * (r * std::cos(phi)) + s * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - a));
}

// The openings this point samples through: in front of it (F above kMinOpeningF) and seen, by one of
// five probes, past the scene's geometry. Those left out are the hemisphere's to sample.
constexpr double kMinOpeningF = 1e-6;
void choose_openings(const RayScene::Openings& open, const Vec3& n, const Vec3& from, const RayScene& rays,
                     std::vector<uint8_t>& chosen, std::vector<double>& F, uint64_t& cast) {
  static constexpr double kProbes[5][2] = {{0.5, 0.5}, {0.15, 0.15}, {0.85, 0.15}, {0.15, 0.85}, {0.85, 0.85}};
  chosen.assign(open.triangles.size(), 0);
  F.assign(open.triangles.size(), 0.0);
  for (size_t k = 0; k < open.triangles.size(); ++k) {
    const Polygon& p = open.triangles[k];
    F[k] = point_to_polygon(from, n, p);
    if (!(F[k] > kMinOpeningF)) continue;
    for (const auto& q : kProbes) {
      ++cast;
      if (!rays.occluded(from, sample_polygon(p, q[0], q[1]))) {
        chosen[k] = 1;
        break;
      }
    }
  }
}

// A direction uniform in solid angle over the spherical triangle of unit vectors a, b, c, from (u, v) in
// [0,1)² (Arvo, "Stratified sampling of spherical triangles", SIGGRAPH 1995). False where the triangle
// is too thin to sample.
bool spherical_triangle_direction(const Vec3& a, const Vec3& b, const Vec3& c, double u, double v, Vec3& out) {
  const auto angle_at = [](const Vec3& p, const Vec3& q, const Vec3& r) {  // between the arcs p→q and p→r
    const Vec3 tq = q - p * dot(p, q), tr = r - p * dot(p, r);
    const double lq = length(tq), lr = length(tr);
    return lq > 0 && lr > 0 ? std::acos(std::clamp(dot(tq, tr) / (lq * lr), -1.0, 1.0)) : 0.0;
  };
  const double alpha = angle_at(a, b, c), at_b = angle_at(b, c, a), at_c = angle_at(c, a, b);
  const double area = alpha + at_b + at_c - kPi;
  if (!(area > 1e-12) || !(std::sin(alpha) > 1e-12)) return false;
  const double sub = u * area, s = std::sin(sub - alpha), t = std::cos(sub - alpha);
  const double cos_c = dot(a, b);
  const double uu = t - std::cos(alpha), vv = s + std::sin(alpha) * cos_c;
  const double q = std::clamp(((vv * t - uu * s) * std::cos(alpha) - vv) / ((vv * s + uu * t) * std::sin(alpha)), -1.0, 1.0);
  const Vec3 ca = c - a * dot(c, a);
  if (!(length(ca) > 0)) return false;
  const Vec3 c2 = a * q + normalize(ca) * std::sqrt(std::max(0.0, 1 - q * q));
  const double z = 1 - v * (1 - dot(c2, b));
  const Vec3 cb = c2 - b * dot(c2, b);
  out = length(cb) > 0 ? normalize(b * z + normalize(cb) * std::sqrt(std::max(0.0, 1 - z * z))) : b;
  return true;
}

// π F ⟨L V⟩ over the opening's triangle: side × side stratified directions uniform in the solid angle it
// subtends, each weighed by its cosine at the point (so that the weights' mean stands for F, taken exact
// from the contour formula; near a window, where the kernel varies a hundredfold over it, points drawn
// by area left a pane's Fresnel falloff 6% off); a direction counts where its ray crosses this opening
// before any other and then leaves the scene, times the clear glass it crosses.
Vec3 through_opening(const Sky& sky, const RayScene::Openings& open, size_t k, double F, const Vec3& n, const Vec3& from,
                     const RayScene& rays, double far, int side, uint64_t& cast) {
  const Polygon& p = open.triangles[k];
  const Vec3 a = normalize(p.v[0] - from), b = normalize(p.v[1] - from), c = normalize(p.v[2] - from);
  Vec3 sum;
  double weight = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      Vec3 w;
      if (!spherical_triangle_direction(a, b, c, (i + 0.5) / side, (j + 0.5) / side, w)) return {};
      const double g = dot(n, w);
      if (!(g > 0)) continue;
      weight += g;
      const Vec3 L = sky.at(w);
      if (max_component(L) <= 0) continue;
      cast += 2;
      const RayScene::Hit first = open.rays->intersect(from, w);
      if (!first.hit || first.polygon != k || rays.occluded(from, from + w * far)) continue;
      sum += mul(L, rays.transmittance(from, from + w * far)) * g;
    }
  return weight > 0 ? sum * (kPi * F / weight) : Vec3{};
}

struct Cell {
  int i, j;    // row (a) and column (b) at its level
  Vec3 value;  // L·V through its centre
};

}  // namespace

Vec3 sky_irradiance(const Sky& sky, const Vec3& n, const Vec3& from, const RayScene* rays, const SkyPattern& pattern,
                    uint64_t& rays_cast) {
  Vec3 t, s;
  frame(n, t, s);
  const int levels = pattern.levels, res = pattern.base << levels;
  const double far = rays ? 2e6 * rays->offset() : 0;  // twice the scene's diagonal (RayScene::offset)
  thread_local std::vector<float> lum;                 // the finest cells' luminance, painted by each level
  thread_local std::vector<Cell> cells, next;
  thread_local std::vector<uint8_t> split;
  thread_local std::vector<uint8_t> chosen;
  thread_local std::vector<double> F;
  lum.assign(size_t(res) * size_t(res), 0.0f);
  uint64_t cast = 0;
  // Through the openings first; the hemisphere then takes every direction that crosses none of the
  // chosen ones first (a partition of the directions: nothing is counted twice, nothing left out).
  const RayScene::Openings* open = rays && rays->openings() && rays->openings()->rays ? rays->openings() : nullptr;
  Vec3 through;
  if (open) {
    choose_openings(*open, n, from, *rays, chosen, F, cast);
    for (size_t k = 0; k < chosen.size(); ++k)
      if (chosen[k]) through += through_opening(sky, *open, k, F[k], n, from, *rays, far, pattern.opening_side, cast);
  }
  const auto evaluate = [&](int level, Cell& c) {
    const int side = pattern.base << level;
    const Vec3 w = direction(n, t, s, (c.i + 0.5) / side, (c.j + 0.5) / side);
    c.value = sky.at(w);
    if (max_component(c.value) <= 0 || !rays) return;
    if (open) {
      ++cast;
      const RayScene::Hit first = open->rays->intersect(from, w);
      if (first.hit && chosen[first.polygon]) {
        c.value = {};
        return;
      }
    }
    ++cast;
    c.value = rays->occluded(from, from + w * far) ? Vec3{} : mul(c.value, rays->transmittance(from, from + w * far));
  };
  const auto paint = [&](int level, const Cell& c) {
    const int size = 1 << (levels - level);
    const float l = float(luminance(c.value));
    for (int r = c.i * size; r < (c.i + 1) * size; ++r)
      for (int q = c.j * size; q < (c.j + 1) * size; ++q) lum[size_t(r) * size_t(res) + size_t(q)] = l;
  };
  const double threshold = kSkyContrast * sky.mean_luminance;
  // Whether a finest cell along c's edges (and, at the zenith, the cells across it) differs from c.
  const auto differs = [&](int level, const Cell& c) {
    const int size = 1 << (levels - level), side = pattern.base << level;
    const float own = float(luminance(c.value));
    const auto other = [&](int r, int q) { return std::fabs(lum[size_t(r) * size_t(res) + size_t((q % res + res) % res)] - own) > threshold; };
    for (int k = 0; k < size; ++k) {
      const int r = c.i * size + k, q = c.j * size + k;
      if (c.i > 0 && other(c.i * size - 1, q)) return true;
      if (c.i + 1 < side && other((c.i + 1) * size, q)) return true;
      if (c.i == 0 && other(0, q + res / 2)) return true;
      if (other(r, c.j * size - 1) || other(r, (c.j + 1) * size)) return true;
    }
    return false;
  };

  cells.clear();
  for (int i = 0; i < pattern.base; ++i)
    for (int j = 0; j < pattern.base; ++j) {
      Cell c{i, j, {}};
      evaluate(0, c);
      paint(0, c);
      cells.push_back(c);
    }
  Vec3 total;
  int level = 0;
  for (; level < levels; ++level) {
    const double share = 1.0 / (double(pattern.base << level) * double(pattern.base << level));
    next.clear();
    split.assign(cells.size(), 0);
    size_t count = 0;
    for (size_t k = 0; k < cells.size(); ++k) count += split[k] = differs(level, cells[k]) ? 1 : 0;
    if (count == 0 || cast + 4 * count > uint64_t(pattern.budget)) break;
    for (size_t k = 0; k < cells.size(); ++k) {
      const Cell& c = cells[k];
      if (!split[k]) {
        total += c.value * share;
        continue;
      }
      for (int d = 0; d < 4; ++d) next.push_back({2 * c.i + d / 2, 2 * c.j + d % 2, {}});
    }
    for (Cell& c : next) evaluate(level + 1, c);
    for (const Cell& c : next) paint(level + 1, c);
    cells.swap(next);
  }
  const double share = 1.0 / (double(pattern.base << level) * double(pattern.base << level));
  for (const Cell& c : cells) total += c.value * share;
  rays_cast += cast;
  return total * kPi + through;
}

double sky_power(const Sky& sky, const std::vector<Polygon>& polygons) {
  double power = 0;
  for (const Polygon& p : polygons)
    power += polygon_area(p) * (sky.kind == Sky::Kind::image ? 1.0 : 0.5 * (1 + dot(polygon_normal(p), sky.up)));
  return power * kPi * sky.mean_luminance;
}

}  // namespace walkrad
