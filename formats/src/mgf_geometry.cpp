// MGF faces → convex triangles and quads (mgf_geometry.h): convex fans, ear clipping, hole bridges.
// Ear clipping and hole bridging follow D. Eberly, "Triangulation by Ear Clipping" (Geometric
// Tools, 2002): an ear is a convex corner whose triangle holds no other vertex; a hole is joined to
// the outline through its rightmost vertex and the outline vertex it sees along +x.
#include "mgf_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace walkrad::mgf {

namespace {


struct Vec2 {
  double x = 0, y = 0;
};
Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
double cross2(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
double dot2(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double length2(Vec2 a) { return std::sqrt(dot2(a, a)); }

Vec3 newell(const Loop& l) {
  Vec3 n;
  for (size_t i = 0; i < l.size(); ++i) n += cross(l[i], l[(i + 1) % l.size()]);
  return n;
}

double extent(const Loop& l) {
  Bounds b;
  for (const Vec3& p : l) b.extend(p);
  return length(b.diagonal());
}

// A 2D frame in the plane normal to n: (u, v, n) right-handed, so counter-clockwise about n is
// counter-clockwise in (u, v).
struct Frame {
  Vec3 origin, u, v;
  Vec2 project(const Vec3& p) const { return {dot(p - origin, u), dot(p - origin, v)}; }
};
Frame frame_for(const Vec3& origin, const Vec3& n) {
  const Vec3 helper = std::fabs(n.x) < 0.6 ? Vec3{1, 0, 0} : (std::fabs(n.y) < 0.6 ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
  const Vec3 v = normalize(cross(n, cross(helper, n)));  // helper's part normal to n
  return {origin, cross(v, n), v};
}

// Ear clipping of a counter-clockwise 2D outline (seams allowed). Appends index triples; returns
// false when it got stuck (a self-intersecting outline).
bool ear_clip(const std::vector<Vec2>& p, double eps_area, double eps_len, std::vector<std::array<size_t, 3>>& tris) {
  std::vector<size_t> idx(p.size());
  std::iota(idx.begin(), idx.end(), 0);
  auto same = [&](size_t a, size_t b) { return length2(p[a] - p[b]) <= eps_len; };
  auto corner = [&](size_t k) {
    const size_t m = idx.size();
    return cross2(p[idx[k]] - p[idx[(k + m - 1) % m]], p[idx[(k + 1) % m]] - p[idx[k]]);
  };
  auto is_ear = [&](size_t k) {
    const size_t m = idx.size();
    const size_t i0 = idx[(k + m - 1) % m], i1 = idx[k], i2 = idx[(k + 1) % m];
    if (corner(k) <= eps_area) return false;
    const Vec2 a = p[i0], b = p[i1], c = p[i2];
    for (size_t j = 0; j < m; ++j) {
      const size_t q = idx[j];
      if (same(q, i0) || same(q, i1) || same(q, i2)) continue;
      if (cross2(b - a, p[q] - a) >= -eps_area && cross2(c - b, p[q] - b) >= -eps_area &&
          cross2(a - c, p[q] - c) >= -eps_area)
        return false;  // a vertex inside or on the triangle
    }
    // The new edge c→a must not cross an outline edge.
    for (size_t j = 0; j < m; ++j) {
      const size_t e0 = idx[j], e1 = idx[(j + 1) % m];
      if (same(e0, i0) || same(e0, i2) || same(e1, i0) || same(e1, i2)) continue;
      const double d0 = cross2(a - c, p[e0] - c), d1 = cross2(a - c, p[e1] - c);
      const double d2 = cross2(p[e1] - p[e0], c - p[e0]), d3 = cross2(p[e1] - p[e0], a - p[e0]);
      if (((d0 > eps_area && d1 < -eps_area) || (d0 < -eps_area && d1 > eps_area)) &&
          ((d2 > eps_area && d3 < -eps_area) || (d2 < -eps_area && d3 > eps_area)))
        return false;
    }
    return true;
  };
  while (idx.size() > 3) {
    bool clipped = false;
    for (size_t k = 0; k < idx.size() && !clipped; ++k) {
      if (!is_ear(k)) continue;
      const size_t m = idx.size();
      tris.push_back({idx[(k + m - 1) % m], idx[k], idx[(k + 1) % m]});
      idx.erase(idx.begin() + long(k));
      clipped = true;
    }
    if (clipped) continue;
    // No ear: drop a corner without area (collinear, or a seam's turn-back), else give up.
    size_t flat = idx.size();
    for (size_t k = 0; k < idx.size() && flat == idx.size(); ++k)
      if (std::fabs(corner(k)) <= eps_area) flat = k;
    if (flat == idx.size()) return false;
    idx.erase(idx.begin() + long(flat));
  }
  if (idx.size() == 3 && corner(1) > eps_area) tris.push_back({idx[0], idx[1], idx[2]});
  return true;
}

}  // namespace

SplitResult split_face(const Loop& face) {
  SplitResult r;
  const double size = extent(face);
  Loop l;
  for (const Vec3& p : face)
    if (l.empty() || length(p - l.back()) > 1e-12 * size) l.push_back(p);
  while (l.size() > 1 && length(l.front() - l.back()) <= 1e-12 * size) l.pop_back();
  const Vec3 area_normal = newell(l);
  if (l.size() < 3 || !(length(area_normal) > 1e-12 * size * size)) {
    r.degenerate = true;
    return r;
  }
  const Vec3 n = normalize(area_normal);
  Vec3 centre;
  for (const Vec3& p : l) centre += p / double(l.size());
  bool planar = true;
  for (const Vec3& p : l) planar = planar && std::fabs(dot(p - centre, n)) <= 1e-6 * size;
  if (l.size() == 3) {
    r.pieces.push_back(l);
    return r;
  }
  const Frame f = frame_for(centre, n);
  std::vector<Vec2> p2(l.size());
  for (size_t i = 0; i < l.size(); ++i) p2[i] = f.project(l[i]);
  const double eps_area = 1e-12 * size * size;

  // Convex: every corner turns left (or goes straight on) and the outline turns once around.
  bool convex = planar;
  double turning = 0;
  std::vector<size_t> corners;  // the corners that turn
  for (size_t i = 0; i < l.size() && convex; ++i) {
    const Vec2 e0 = p2[i] - p2[(i + l.size() - 1) % l.size()], e1 = p2[(i + 1) % l.size()] - p2[i];
    const double c = cross2(e0, e1);
    turning += std::atan2(c, dot2(e0, e1));
    if (c < -eps_area) convex = false;
    else if (c > eps_area) corners.push_back(i);
    else if (dot2(e0, e1) < 0) convex = false;  // turns back on itself
  }
  if (convex && std::fabs(turning - 2 * kPi) < 1e-6 && corners.size() >= 3) {
    // A fan of quads from the first corner: each is a convex piece of a convex face.
    size_t k = 1;
    while (k + 2 < corners.size()) {
      r.pieces.push_back({l[corners[0]], l[corners[k]], l[corners[k + 1]], l[corners[k + 2]]});
      k += 2;
    }
    if (k + 1 < corners.size()) r.pieces.push_back({l[corners[0]], l[corners[k]], l[corners[k + 1]]});
    return r;
  }
  r.nonplanar = !planar;
  std::vector<std::array<size_t, 3>> tris;
  r.untriangulated = !ear_clip(p2, eps_area, 1e-9 * size, tris);
  for (const auto& t : tris) r.pieces.push_back({l[t[0]], l[t[1]], l[t[2]]});
  if (r.pieces.empty() && !r.untriangulated) r.degenerate = true;
  return r;
}

namespace {

// The outline vertex P a bridge from a hole's rightmost vertex M joins (hole joining as in Eberly,
// "Triangulation by Ear Clipping", 2002): the nearer end of the first outline edge the ray from M along
// +x meets, unless a reflex vertex inside the triangle (M, hit, P) hides it. loop.size(): the ray meets
// no edge (the hole is not inside the outline).
size_t bridge_end(const std::vector<size_t>& loop, const std::vector<Vec2>& p2, Vec2 m, double size, double eps) {
  // The nearest outline edge hit by the ray from M along +x.
  double best_x = INFINITY;
  size_t edge = loop.size();
  for (size_t i = 0; i < loop.size(); ++i) {
    const Vec2 a = p2[loop[i]], b = p2[loop[(i + 1) % loop.size()]];
    if ((a.y > m.y) == (b.y > m.y) && a.y != m.y && b.y != m.y) continue;
    if (a.y == b.y) continue;  // along the ray: its end points are found through the next edges
    const double x = a.x + (m.y - a.y) * (b.x - a.x) / (b.y - a.y);
    if (x >= m.x && x < best_x) {
      best_x = x;
      edge = i;
    }
  }
  if (edge == loop.size()) return loop.size();
  const Vec2 hit{best_x, m.y};
  const size_t ea = edge, eb = (edge + 1) % loop.size();
  size_t pick = p2[loop[ea]].x > p2[loop[eb]].x ? ea : eb;
  if (length2(p2[loop[ea]] - hit) <= 1e-9 * size) pick = ea;
  else if (length2(p2[loop[eb]] - hit) <= 1e-9 * size) pick = eb;
  else {
    // A reflex outline vertex inside triangle (M, hit, P) hides P: take the one closest in angle to +x.
    const Vec2 pv = p2[loop[pick]];
    const bool ccw = cross2(hit - m, pv - m) > 0;
    double best_cos = -2, best_dist = INFINITY;
    for (size_t i = 0; i < loop.size(); ++i) {
      if (i == pick) continue;
      const Vec2 q = p2[loop[i]];
      const Vec2 prev = p2[loop[(i + loop.size() - 1) % loop.size()]], next = p2[loop[(i + 1) % loop.size()]];
      if (cross2(q - prev, next - q) >= 0) continue;  // not reflex
      const Vec2 t0 = m, t1 = ccw ? hit : pv, t2 = ccw ? pv : hit;
      if (cross2(t1 - t0, q - t0) < -eps || cross2(t2 - t1, q - t1) < -eps || cross2(t0 - t2, q - t2) < -eps) continue;
      const double d = length2(q - m), c = (q.x - m.x) / d;
      if (c > best_cos + 1e-12 || (std::fabs(c - best_cos) <= 1e-12 && d < best_dist)) {
        best_cos = c;
        best_dist = d;
        pick = i;
      }
    }
  }
  // P may be in the loop more than once (earlier bridges end there): take the occurrence whose
  // corner holds the bridge, so that bridges at one vertex do not cross.
  {
    const Vec2 pv = p2[loop[pick]], d = m - pv;
    auto angle = [](Vec2 from, Vec2 to) {  // counter-clockwise, in [0, 2π)
      const double a = std::atan2(cross2(from, to), dot2(from, to));
      return a < 0 ? a + 2 * kPi : a;
    };
    for (size_t i = 0; i < loop.size(); ++i) {
      if (length2(p2[loop[i]] - pv) > 1e-9 * size) continue;
      const Vec2 out = p2[loop[(i + 1) % loop.size()]] - pv, back = p2[loop[(i + loop.size() - 1) % loop.size()]] - pv;
      if (angle(out, d) <= angle(out, back)) {
        pick = i;
        break;
      }
    }
  }
  return pick;
}

}  // namespace

bool join_holes(const Loop& outline, const std::vector<Loop>& holes, Loop& joined, std::string& why) {
  const Vec3 an = newell(outline);
  const double size = extent(outline);
  if (outline.size() < 3 || !(length(an) > 1e-12 * size * size)) {
    why = "the outline has no area";
    return false;
  }
  const Frame f = frame_for(outline[0], normalize(an));
  const double eps = 1e-12 * size * size;
  // Every point once, in 3D and projected; loops are index lists.
  std::vector<Vec3> pts(outline);
  std::vector<size_t> loop(outline.size());
  std::iota(loop.begin(), loop.end(), 0);
  std::vector<std::vector<size_t>> hole_loops;
  for (size_t h = 0; h < holes.size(); ++h) {
    std::vector<size_t> hl;
    for (const Vec3& p : holes[h]) {
      hl.push_back(pts.size());
      pts.push_back(p);
    }
    hole_loops.push_back(hl);
  }
  std::vector<Vec2> p2(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) p2[i] = f.project(pts[i]);
  auto signed_area = [&](const std::vector<size_t>& l) {
    double a = 0;
    for (size_t i = 0; i < l.size(); ++i) a += cross2(p2[l[i]], p2[l[(i + 1) % l.size()]]);
    return a / 2;
  };
  auto inside = [&](const std::vector<size_t>& l, Vec2 q) {  // even-odd rule
    bool in = false;
    for (size_t i = 0, j = l.size() - 1; i < l.size(); j = i++) {
      const Vec2 a = p2[l[i]], b = p2[l[j]];
      if ((a.y > q.y) != (b.y > q.y) && q.x < (b.x - a.x) * (q.y - a.y) / (b.y - a.y) + a.x) in = !in;
    }
    return in;
  };
  std::vector<size_t> order(holes.size());
  std::vector<size_t> rightmost(holes.size());
  for (size_t h = 0; h < holes.size(); ++h) {
    std::vector<size_t>& hl = hole_loops[h];
    if (hl.size() < 3 || std::fabs(signed_area(hl)) <= eps) {
      why = "hole " + std::to_string(h + 1) + " has no area";
      return false;
    }
    if (signed_area(hl) > 0) std::reverse(hl.begin(), hl.end());  // holes run clockwise
    for (size_t i : hl)
      if (!inside(loop, p2[i])) {
        why = "hole " + std::to_string(h + 1) + " is not inside the outline";
        return false;
      }
    size_t best = 0;
    for (size_t i = 1; i < hl.size(); ++i)
      if (p2[hl[i]].x > p2[hl[best]].x) best = i;
    rightmost[h] = best;
    order[h] = h;
  }
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return p2[hole_loops[a][rightmost[a]]].x > p2[hole_loops[b][rightmost[b]]].x; });

  for (size_t h : order) {
    const std::vector<size_t>& hl = hole_loops[h];
    const size_t mi = hl[rightmost[h]];
    const Vec2 m = p2[mi];
    const size_t pick = bridge_end(loop, p2, m, size, eps);
    if (pick == loop.size()) {
      why = "hole " + std::to_string(h + 1) + " is not inside the outline";
      return false;
    }
    // Splice: ..., P, M, (the rest of the hole from M), M, P, ...
    std::vector<size_t> splice;
    for (size_t k = 0; k <= hl.size(); ++k) splice.push_back(hl[(rightmost[h] + k) % hl.size()]);
    splice.push_back(loop[pick]);
    loop.insert(loop.begin() + long(pick) + 1, splice.begin(), splice.end());
  }
  joined.clear();
  for (size_t i : loop) joined.push_back(pts[i]);
  return true;
}

}  // namespace walkrad::mgf
