// sky_irradiance (sky_light.h): the cosine-weighted square cut adaptively where what the point sees of
// the sky changes.
#include "walkrad/formfactor/sky_light.h"

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

// π F ⟨L V⟩ over the opening: side × side stratified points y of it, each weighed by the kernel
// cos θx cos θy / r² (so that the weights' mean stands for F, taken exact from the contour formula); a
// point counts where its ray crosses this opening before any other and then leaves the scene.
Vec3 through_opening(const Sky& sky, const RayScene::Openings& open, size_t k, double F, const Vec3& n, const Vec3& from,
                     const RayScene& rays, double far, int side, uint64_t& cast) {
  const Polygon& p = open.triangles[k];
  const Vec3 np = polygon_normal(p);
  Vec3 sum;
  double weight = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const Vec3 d = sample_polygon(p, (i + 0.5) / side, (j + 0.5) / side) - from;
      const double r2 = dot(d, d);
      if (!(r2 > 0)) continue;
      const Vec3 w = d / std::sqrt(r2);
      const double g = dot(n, w) * std::fabs(dot(np, w)) / r2;
      if (!(g > 0)) continue;
      weight += g;
      const Vec3 L = sky.at(w);
      if (max_component(L) <= 0) continue;
      cast += 2;
      const RayScene::Hit first = open.rays->intersect(from, w);
      if (!first.hit || first.polygon != k || rays.occluded(from, from + w * far)) continue;
      sum += L * g;
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
    if (rays->occluded(from, from + w * far)) c.value = {};
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
    std::vector<uint8_t> split(cells.size(), 0);
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

Vec3 open_sky_irradiance(const Sky& sky, const Vec3& n) {
  Vec3 t, s;
  frame(n, t, s);
  constexpr int kSide = 256;
  Vec3 total;
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j) total += sky.at(direction(n, t, s, (i + 0.5) / kSide, (j + 0.5) / kSide));
  return total * (kPi / (kSide * kSide));
}

double sky_power(const Sky& sky, const std::vector<Polygon>& polygons) {
  double power = 0;
  for (const Polygon& p : polygons)
    power += polygon_area(p) * (sky.kind == Sky::Kind::image ? 1.0 : 0.5 * (1 + dot(polygon_normal(p), sky.up)));
  return power * kPi * sky.mean_luminance;
}

}  // namespace walkrad
