#include "walkrad/formats/scene.h"

#include <cmath>

namespace walkrad {

Vec3 polygon_area_normal(const Polygon& p) {
  // Newell's method: exact for planar polygons, a best-fit normal for slightly non-planar quads. On
  // corners relative to the first one (the sum does not change): products of absolute coordinates
  // cancel catastrophically far from the origin (a 5 cm element 1.7e5 m away lost 1e-3 of its area).
  Vec3 n;
  for (int i = 1; i + 1 < p.count; ++i) n += cross(p.v[i] - p.v[0], p.v[i + 1] - p.v[0]);
  return n;
}

Vec3 polygon_normal(const Polygon& p) { return normalize(polygon_area_normal(p)); }

double polygon_area(const Polygon& p) { return 0.5 * length(polygon_area_normal(p)); }

Vec3 polygon_centroid(const Polygon& p) {
  if (p.count == 3) return (p.v[0] + p.v[1] + p.v[2]) / 3.0;
  // Quad: area-weighted centroids of the two triangles of a fan.
  const double a0 = length(cross(p.v[1] - p.v[0], p.v[2] - p.v[0]));
  const double a1 = length(cross(p.v[2] - p.v[0], p.v[3] - p.v[0]));
  const Vec3 c0 = (p.v[0] + p.v[1] + p.v[2]) / 3.0, c1 = (p.v[0] + p.v[2] + p.v[3]) / 3.0;
  return a0 + a1 > 0 ? (c0 * a0 + c1 * a1) / (a0 + a1) : c0;
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const Polygon& p : polygons)
    for (int i = 0; i < p.count; ++i) b.extend(p.v[i]);
  return b;
}

}  // namespace walkrad

namespace walkrad {

Vec3 Texture::at(double u, double v) const {
  if (width == 0 || height == 0) return {1, 1, 1};
  // Texel centres at (i + 0.5) / width; repeat wrapping.
  const double x = u * width - 0.5, y = v * height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = x - fx, ty = y - fy;
  auto wrap = [](long long i, uint32_t n) { return uint32_t(((i % static_cast<long long>(n)) + n) % n); };
  auto texel = [&](long long i, long long j) {
    const size_t k = (size_t(wrap(j, height)) * width + wrap(i, width)) * 3;
    return Vec3(rgb[k], rgb[k + 1], rgb[k + 2]);
  };
  const long long i = (long long)fx, j = (long long)fy;
  return (texel(i, j) * (1 - tx) + texel(i + 1, j) * tx) * (1 - ty) + (texel(i, j + 1) * (1 - tx) + texel(i + 1, j + 1) * tx) * ty;
}

}  // namespace walkrad
