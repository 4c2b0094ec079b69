#include "walkrad/classic/subdivision.h"

#include <algorithm>
#include <cmath>

namespace walkrad {

namespace {

int segments(double length, double target) { return std::max(1, int(std::ceil(length / target - 1e-9))); }

void add_element(Subdivision& s, const Polygon& poly, uint32_t index, std::array<uint32_t, 4> corners, int count) {
  Element e;
  e.shape.count = uint8_t(count);
  e.shape.material = poly.material;
  e.shape.source = poly.source;
  e.shape.uv = poly.uv;
  for (int k = 0; k < count; ++k) e.shape.v[k] = s.vertices[corners[k]];
  e.corner = corners;
  e.normal = polygon_normal(e.shape);
  e.centroid = polygon_centroid(e.shape);
  e.area = polygon_area(e.shape);
  e.polygon = index;
  if (e.area > 0) s.elements.push_back(e);
}

void subdivide_quad(Subdivision& s, const Polygon& p, uint32_t index, double h) {
  const auto& v = p.v;
  const int nu = segments(std::max(length(v[1] - v[0]), length(v[2] - v[3])), h);
  const int nv = segments(std::max(length(v[3] - v[0]), length(v[2] - v[1])), h);
  const uint32_t base = uint32_t(s.vertices.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const double a = double(i) / nu, b = double(j) / nv;
      s.vertices.push_back(v[0] * ((1 - a) * (1 - b)) + v[1] * (a * (1 - b)) + v[2] * (a * b) + v[3] * ((1 - a) * b));
    }
  auto at = [&](int i, int j) { return base + uint32_t(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) add_element(s, p, index, {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}, 4);
}

void subdivide_triangle(Subdivision& s, const Polygon& p, uint32_t index, double h) {
  const auto& v = p.v;
  const int n = segments(std::max({length(v[1] - v[0]), length(v[2] - v[1]), length(v[0] - v[2])}), h);
  const uint32_t base = uint32_t(s.vertices.size());
  // Row j holds n - j + 1 vertices: v0 + (v1 - v0) i/n + (v2 - v0) j/n.
  std::vector<uint32_t> row_start(n + 2);
  for (int j = 0; j <= n; ++j) {
    row_start[j] = uint32_t(s.vertices.size()) - base;
    for (int i = 0; i <= n - j; ++i) s.vertices.push_back(v[0] + (v[1] - v[0]) * (double(i) / n) + (v[2] - v[0]) * (double(j) / n));
  }
  auto at = [&](int i, int j) { return base + row_start[j] + uint32_t(i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n - j; ++i) {
      add_element(s, p, index, {at(i, j), at(i + 1, j), at(i, j + 1), 0}, 3);
      if (i + 1 < n - j) add_element(s, p, index, {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), 0}, 3);
    }
}

}  // namespace

Subdivision subdivide_uniform(const Scene& scene, double target_size) {
  Subdivision s;
  s.first_element.reserve(scene.polygons.size() + 1);
  for (uint32_t p = 0; p < scene.polygons.size(); ++p) {
    s.first_element.push_back(uint32_t(s.elements.size()));
    const Polygon& poly = scene.polygons[p];
    if (poly.count == 4) subdivide_quad(s, poly, p, target_size);
    else subdivide_triangle(s, poly, p, target_size);
  }
  s.first_element.push_back(uint32_t(s.elements.size()));
  return s;
}

}  // namespace walkrad
