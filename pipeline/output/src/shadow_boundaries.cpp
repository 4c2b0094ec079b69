#include "walkrad/output/shadow_boundaries.h"

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>

#include "walkrad/scene/convex_loop.h"

namespace walkrad {

namespace {

// Clips segment [a, b] on the receiver's plane to the convex receiver.
bool clip_to(const Polygon& q, const Vec3& qn, Vec3& a, Vec3& b, double tol) {
  double t0, t1;
  if (!clip_segment(q.v.data(), q.count, qn, a, b, t0, t1)) return false;
  const Vec3 a0 = a, d = b - a;
  a = a0 + d * t0;
  b = a0 + d * t1;
  return length(b - a) > tol;
}

// The part [t0, t1] of segment [a, b] whose height h(t) = ha + t (hb − ha) lies in [lo, hi].
bool height_range(double ha, double hb, double lo, double hi, double& t0, double& t1) {
  t0 = 0;
  t1 = 1;
  if (ha == hb) return ha >= lo && ha <= hi;
  const double u = (lo - ha) / (hb - ha), w = (hi - ha) / (hb - ha);
  t0 = std::max(0.0, std::min(u, w));
  t1 = std::min(1.0, std::max(u, w));
  return t1 > t0;
}

// Clips segment [a, b] to the box (padded by pad): false where nothing of it is inside (slabs).
bool clip_to_box(const Bounds& box, double pad, Vec3& a, Vec3& b) {
  double t0 = 0, t1 = 1;
  const Vec3 d = b - a;
  const double lo[3] = {box.lo.x - pad, box.lo.y - pad, box.lo.z - pad}, hi[3] = {box.hi.x + pad, box.hi.y + pad, box.hi.z + pad};
  const double o[3] = {a.x, a.y, a.z}, v[3] = {d.x, d.y, d.z};
  for (int k = 0; k < 3; ++k) {
    if (v[k] == 0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    const double u0 = (lo[k] - o[k]) / v[k], u1 = (hi[k] - o[k]) / v[k];
    t0 = std::max(t0, std::min(u0, u1));
    t1 = std::min(t1, std::max(u0, u1));
    if (t0 >= t1) return false;
  }
  const Vec3 a0 = a;
  a = a0 + d * t0;
  b = a0 + d * t1;
  return length(b - a) > pad;
}

}  // namespace

std::vector<BoundarySegment> shadow_boundaries(const Polygon& emitter, const Polygon& receiver,
                                               const std::vector<Polygon>& occluders, double tol, const Bounds* within) {
  std::vector<BoundarySegment> out;
  const Vec3 qn = polygon_normal(receiver), en = polygon_normal(emitter);
  const Vec3 q0 = receiver.v[0];
  auto height = [&](const Vec3& x) { return dot(x - q0, qn); };
  if (dot(polygon_centroid(receiver) - emitter.v[0], en) <= 0) return out;  // the receiver is behind the emitter

  // Each occluder edge's neighbours: the occluders with an edge between the same two corners, found
  // by sorting the edges on their corners rounded to the tolerance (lower corner first).
  struct Edge {
    uint32_t occluder;
    int k;
  };
  struct Key {
    std::array<int64_t, 6> corners;
    Edge edge;
  };
  auto grid = [&](const Vec3& x) {
    return std::array<int64_t, 3>{std::llround(x.x / tol), std::llround(x.y / tol), std::llround(x.z / tol)};
  };
  std::vector<Key> keys;
  for (uint32_t o = 0; o < occluders.size(); ++o)
    for (int k = 0; k < occluders[o].count; ++k) {
      std::array<int64_t, 3> a = grid(occluders[o].v[k]), b = grid(occluders[o].v[(k + 1) % occluders[o].count]);
      if (b < a) std::swap(a, b);
      keys.push_back({{a[0], a[1], a[2], b[0], b[1], b[2]}, {o, k}});
    }
  std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) {
    return x.corners != y.corners ? x.corners < y.corners
                                  : std::make_pair(x.edge.occluder, x.edge.k) < std::make_pair(y.edge.occluder, y.edge.k);
  });
  std::vector<std::vector<Edge>> shared(occluders.size() * 4);
  for (size_t first = 0, last; first < keys.size(); first = last) {
    for (last = first + 1; last < keys.size() && keys[last].corners == keys[first].corners;) ++last;
    for (size_t x = first; x < last; ++x)
      for (size_t y = first; y < last; ++y)
        if (x != y) shared[keys[x].edge.occluder * 4 + size_t(keys[x].edge.k)].push_back(keys[y].edge);
  }
  std::vector<Vec3> normal(occluders.size());
  for (size_t o = 0; o < occluders.size(); ++o) normal[o] = polygon_normal(occluders[o]);
  auto faces = [&](uint32_t o, const Vec3& x) { return dot(x - occluders[o].v[0], normal[o]) > 0; };
  auto silhouette = [&](uint32_t o, int k, const Vec3& x) {
    if (shared[o * 4 + k].empty()) return true;
    const bool f = faces(o, x);
    for (const Edge& e : shared[o * 4 + k])
      if (faces(e.occluder, x) != f) return true;
    return false;
  };
  // flips(middle): the emitter point seen to appear or vanish there.
  auto add = [&](Vec3 a, Vec3 b, const auto& flips) {
    if (clip_to(receiver, qn, a, b, tol) && (!within || clip_to_box(*within, tol, a, b)))
      out.push_back({a, b, flips((a + b) * 0.5)});
  };
  // Heights of the points that cast: below the emitter's corner (or edge point) by a thousandth of
  // its height at least, so that a projection stays within a thousand times the distance.
  constexpr double kNearEmitter = 1e-3;

  Vec3 centre = polygon_centroid(emitter);
  for (uint32_t o = 0; o < occluders.size(); ++o) {
    const Polygon& p = occluders[o];
    bool in_plane = true;
    for (int k = 0; k < p.count; ++k) in_plane = in_plane && std::fabs(height(p.v[k])) <= tol;
    if (in_plane) continue;
    for (int k = 0; k < p.count; ++k) {
      const Vec3 a = p.v[k], b = p.v[(k + 1) % p.count];
      const double ha = height(a), hb = height(b);
      // EV: the edge's shadow from each emitter corner that sees it as a silhouette.
      for (int c = 0; c < emitter.count; ++c) {
        const Vec3 e = emitter.v[c];
        const double he = height(e);
        double t0, t1;
        if (he <= tol || !silhouette(o, k, e) || !height_range(ha, hb, -tol, he * (1 - kNearEmitter), t0, t1)) continue;
        auto project = [&](double t) {
          const Vec3 x = a + (b - a) * t;
          return e + (x - e) * (he / (he - height(x)));
        };
        add(project(t0), project(t1), [&](const Vec3&) { return e; });
      }
      // VE: each emitter edge's image through this edge's first corner, where the edge is a silhouette
      // from the emitter's centre (its next edge takes the other corner).
      if (!silhouette(o, k, centre) || ha <= tol) continue;
      for (int c = 0; c < emitter.count; ++c) {
        const Vec3 d0 = emitter.v[c], d1 = emitter.v[(c + 1) % emitter.count];
        double t0, t1;
        if (!height_range(height(d0), height(d1), ha * (1 + kNearEmitter) + tol, INFINITY, t0, t1)) continue;
        auto image = [&](double t) {
          const Vec3 x = d0 + (d1 - d0) * t;
          return a + (a - x) * (ha / (height(x) - ha));
        };
        // In line with the middle and the corner a: where that line meets the emitter's plane.
        add(image(t0), image(t1), [&](const Vec3& x) {
          const double along = dot(a - x, en);
          return std::fabs(along) > 0 ? x + (a - x) * (dot(emitter.v[0] - x, en) / along) : d0;
        });
      }
    }
  }
  // One segment per boundary: the edge two occluders share casts it twice, a corner twice.
  auto key = [&](const BoundarySegment& g) {
    std::array<int64_t, 3> a = grid(g.a), b = grid(g.b);
    if (b < a) std::swap(a, b);
    return std::array<int64_t, 6>{a[0], a[1], a[2], b[0], b[1], b[2]};
  };
  std::stable_sort(out.begin(), out.end(), [&](const BoundarySegment& x, const BoundarySegment& y) { return key(x) < key(y); });
  out.erase(std::unique(out.begin(), out.end(), [&](const BoundarySegment& x, const BoundarySegment& y) { return key(x) == key(y); }),
            out.end());
  return out;
}

}  // namespace walkrad
