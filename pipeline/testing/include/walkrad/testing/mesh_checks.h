// Checks on an output mesh, written independently of the mesher they check.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <tuple>
#include <vector>

#include "walkrad/formats/chunk.h"

namespace walkrad::test {

inline Vec3 vertex_position(const ChunkMesh& m, size_t v) {
  return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
}

// T-junctions: (edge, vertex) pairs where a vertex lies inside a triangle's edge (farther than tol
// from both ends, closer than tol to the segment) — a crack, or a pixel dropout, in the making.
// Vertices are bucketed in a grid; each edge visits the cells its bounding box overlaps.
inline size_t count_t_junctions(const ChunkMesh& m, double tol) {
  Bounds b = m.bounds();
  const double cell = std::max(length(b.diagonal()) / 64.0, 1e-12);
  using Key = std::tuple<long, long, long>;
  auto key = [&](const Vec3& p) {
    return Key(long(std::floor((p.x - b.lo.x) / cell)), long(std::floor((p.y - b.lo.y) / cell)), long(std::floor((p.z - b.lo.z) / cell)));
  };
  std::map<Key, std::vector<size_t>> grid;
  for (size_t v = 0; v < m.vertex_count(); ++v) grid[key(vertex_position(m, v))].push_back(v);
  size_t found = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = vertex_position(m, m.indices[3 * t + size_t(k)]), q = vertex_position(m, m.indices[3 * t + size_t((k + 1) % 3)]);
      const Vec3 d = q - p;
      const double len = length(d);
      const Key lo = key(Vec3(std::min(p.x, q.x) - tol, std::min(p.y, q.y) - tol, std::min(p.z, q.z) - tol));
      const Key hi = key(Vec3(std::max(p.x, q.x) + tol, std::max(p.y, q.y) + tol, std::max(p.z, q.z) + tol));
      for (long x = std::get<0>(lo); x <= std::get<0>(hi); ++x)
        for (long y = std::get<1>(lo); y <= std::get<1>(hi); ++y)
          for (long z = std::get<2>(lo); z <= std::get<2>(hi); ++z) {
            const auto it = grid.find(Key(x, y, z));
            if (it == grid.end()) continue;
            for (size_t v : it->second) {
              const Vec3 r = vertex_position(m, v) - p;
              const double s = dot(r, d) / (len * len);
              if (s * len <= tol || (1 - s) * len <= tol) continue;
              if (length(r - d * s) <= tol) {
                ++found;
                if (std::getenv("WALKRAD_DEBUG_T")) std::fprintf(stderr, "T %zu: (%.9g %.9g %.9g) on (%.9g %.9g %.9g)-(%.9g %.9g %.9g) dist %g\n", v, p.x + r.x, p.y + r.y, p.z + r.z, p.x, p.y, p.z, q.x, q.y, q.z, length(r - d * s));
              }
            }
          }
    }
  return found;
}

// The largest difference of display colour between vertices at one position (within tol) with the
// same normal: a colour seam, where one smooth surface has two values at one point.
inline double largest_colour_seam(const ChunkMesh& m, double tol) {
  std::vector<size_t> order(m.vertex_count());
  for (size_t v = 0; v < order.size(); ++v) order[v] = v;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return m.positions[3 * a] < m.positions[3 * b]; });
  double worst = 0;
  for (size_t i = 0; i < order.size(); ++i)
    for (size_t j = i + 1; j < order.size() && m.positions[3 * order[j]] - m.positions[3 * order[i]] <= tol; ++j) {
      const size_t a = order[i], b = order[j];
      if (length(vertex_position(m, a) - vertex_position(m, b)) > tol) continue;
      double n = 0, c = 0;
      for (int k = 0; k < 3; ++k) {
        n += double(m.normals[3 * a + size_t(k)]) * m.normals[3 * b + size_t(k)];
        c = std::max(c, double(std::fabs(m.colors[3 * a + size_t(k)] - m.colors[3 * b + size_t(k)])));
      }
      if (n > 0.9999) worst = std::max(worst, c);
    }
  return worst;
}

}  // namespace walkrad::test
