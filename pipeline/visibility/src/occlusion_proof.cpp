#include "walkrad/visibility/occlusion_proof.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace walkrad {

namespace {

struct P2 {
  double x, y;
};

// A convex polygon in the plane, at most kMaxCorners corners (R's hull from 8 × 8 box corners has at
// most 16; each clip by a line adds at most one). In place, no heap: a large level tries millions.
constexpr int kMaxCorners = 40;
struct Piece {
  std::array<P2, kMaxCorners> p;
  int n = 0;
};

// Copies only the corners in use (a Piece holds room for kMaxCorners: 640 bytes copied per clip
// otherwise, a tenth of a large level's solve).
void assign(Piece& to, const Piece& from) {
  to.n = from.n;
  std::copy_n(from.p.begin(), from.n, to.p.begin());
}

double cross(const P2& o, const P2& a, const P2& b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

double area(const Piece& q) {
  double s = 0;
  for (int k = 0; k < q.n; ++k) {
    const P2& a = q.p[size_t(k)];
    const P2& b = q.p[size_t((k + 1) % q.n)];
    s += a.x * b.y - a.y * b.x;
  }
  return 0.5 * s;
}

// Andrew's monotone chain over points[0, count): the convex hull, counter-clockwise, without collinear
// points; false where it would not fit a Piece.
bool hull(P2* points, int count, Piece& out) {
  std::sort(points, points + count, [](const P2& a, const P2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  out.n = 0;
  if (count < 3) return false;
  std::array<P2, 2 * 64 + 2> h;
  int k = 0;
  for (int i = 0; i < count; ++i) {
    while (k >= 2 && cross(h[size_t(k - 2)], h[size_t(k - 1)], points[i]) <= 0) --k;
    h[size_t(k++)] = points[i];
  }
  for (int i = count - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[size_t(k - 2)], h[size_t(k - 1)], points[i - 1]) <= 0) --k;
    h[size_t(k++)] = points[i - 1];
  }
  if (k - 1 > kMaxCorners) return false;
  out.n = k - 1;
  std::copy(h.begin(), h.begin() + out.n, out.p.begin());
  return out.n >= 3;
}

// The part of a convex polygon on the left of a → b (keep_left) or on its right (Sutherland & Hodgman);
// false where it would not fit (never for the clips below: an n-gon gains at most one corner).
bool clip(const Piece& poly, const P2& a, const P2& b, bool keep_left, Piece& out) {
  out.n = 0;
  for (int k = 0; k < poly.n; ++k) {
    const P2& p = poly.p[size_t(k)];
    const P2& q = poly.p[size_t((k + 1) % poly.n)];
    const double sp = keep_left ? cross(a, b, p) : -cross(a, b, p), sq = keep_left ? cross(a, b, q) : -cross(a, b, q);
    if (out.n + 2 > kMaxCorners) return false;
    if (sp >= 0) out.p[size_t(out.n++)] = p;
    if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
      const double t = sp / (sp - sq);
      out.p[size_t(out.n++)] = {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
    }
  }
  if (out.n < 3) out.n = 0;
  return true;
}

bool boxes_overlap(const Bounds& a, const Bounds& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}

// What is left of R while polygons are taken off it: a few convex pieces. Past these counts the proof
// gives up (nothing proven): a wall is a few quads, not hundreds of tiles.
constexpr size_t kMaxPieces = 64, kMaxCovers = 32;

struct Remains {
  std::vector<Piece> pieces, next;
  bool overflow = false;
  // Takes the convex polygon `cover` (counter-clockwise) off every piece.
  void take(const Piece& cover, double negligible) {
    next.clear();
    Piece inside, outside, rest;
    for (const Piece& piece : pieces) {
      assign(inside, piece);
      for (int e = 0; e < cover.n && inside.n > 0; ++e) {
        const P2& p0 = cover.p[size_t(e)];
        const P2& p1 = cover.p[size_t((e + 1) % cover.n)];
        if (!clip(inside, p0, p1, false, outside) || !clip(inside, p0, p1, true, rest)) {
          overflow = true;
          return;
        }
        if (outside.n > 0 && area(outside) > negligible) {
          if (next.size() >= kMaxPieces) {
            overflow = true;
            return;
          }
          next.push_back(outside);
        }
        assign(inside, rest);
      }
    }
    pieces.swap(next);
  }
};

}  // namespace

OcclusionProof::OcclusionProof(const Scene& scene, const ClusterTree& tree) : scene_(scene), tree_(tree) {
  if (!tree.nodes.empty()) size_ = std::max(length(tree.nodes[0].bounds.diagonal()), 1e-30);
}

OcclusionProof::End OcclusionProof::box(const Bounds& b, uint32_t tree_node, Vec3 (&corners)[8]) {
  for (int c = 0; c < 8; ++c) corners[c] = Vec3(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z);
  return {corners, 8, tree_node};
}

bool OcclusionProof::blocked(const End& a, const End& b, const uint32_t* planes, size_t count) const {
  for (size_t k = 0; k < count; ++k) {
    const Polygon& q = scene_.polygons[planes[k]];
    const Vec3 n = polygon_normal(q);
    if (length(n) == 0) continue;
    // One plane once (coplanar polygons, either facing, give the same proof).
    bool seen = false;
    for (size_t t = 0; t < k && !seen; ++t) {
      const Polygon& o = scene_.polygons[planes[t]];
      seen = std::fabs(dot(polygon_normal(o), n)) > 1 - 1e-12 && std::fabs(dot(o.v[0] - q.v[0], n)) <= 1e-6 * size_;
    }
    if (!seen && blocked_by_plane(a, b, q.v[0], n, planes[k])) return true;
  }
  return false;
}

bool OcclusionProof::blocked_by_plane(const End& a, const End& b, const Vec3& point, const Vec3& normal, uint32_t first) const {
  // Points within tol of the plane lie on it: the rays' own offset (RayScene::offset) is this size.
  const double tol = 1e-6 * size_;
  auto extent = [&](const End& e, double& lo, double& hi) {
    lo = INFINITY;
    hi = -INFINITY;
    for (int k = 0; k < e.count; ++k) {
      const double d = dot(e.corners[k] - point, normal);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  };
  double alo, ahi, blo, bhi;
  extent(a, alo, ahi);
  extent(b, blo, bhi);
  // Each end on its own closed side, and each reaching off the plane (an end in the plane is not
  // separated from anything).
  double sign;
  if (ahi <= tol && blo >= -tol && alo < -tol && bhi > tol) sign = 1;
  else if (alo >= -tol && bhi <= tol && ahi > tol && blo < -tol) sign = -1;
  else return false;
  const Vec3 n = normal * sign;  // from a's side towards b's

  // R: where the segments between the corners cross the plane, in an orthonormal basis of it.
  const Vec3 helper = std::fabs(n.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 u = normalize(cross(n, helper)), v = cross(n, u);
  auto in_plane = [&](const Vec3& x) {
    const Vec3 d = x - point;
    return P2{dot(d, u), dot(d, v)};
  };
  std::array<P2, 64> crossings;
  int count = 0;
  Bounds region;
  for (int i = 0; i < a.count; ++i) {
    const double da = dot(a.corners[i] - point, n);
    for (int j = 0; j < b.count && count < 64; ++j) {
      const double db = dot(b.corners[j] - point, n);
      const Vec3 x = da >= -tol ? a.corners[i] : db <= tol ? b.corners[j] : a.corners[i] + (b.corners[j] - a.corners[i]) * (da / (da - db));
      crossings[size_t(count++)] = in_plane(x);
      region.extend(x - n * dot(x - point, n));
    }
  }
  thread_local Remains left;
  left.pieces.clear();
  left.overflow = false;
  Piece whole;
  if (!hull(crossings.data(), count, whole)) return false;
  const double total = area(whole);
  if (!(total > 0)) return false;  // the segments cross along a line: no area to cover, nothing proven
  left.pieces.push_back(whole);
  const double negligible = 1e-9 * total;

  // A polygon lying in the plane: taken off R, unless it belongs to a cluster end and faces the other
  // end (it would send light past the cover). Returns false where the proof must give up.
  size_t covers = 0;
  auto cover = [&](uint32_t k) {
    const Polygon& q = scene_.polygons[k];
    for (int c = 0; c < q.count; ++c)
      if (std::fabs(dot(q.v[c] - point, n)) > tol) return true;  // not in the plane: nothing to take
    if (++covers > kMaxCovers) return false;
    const double facing = dot(polygon_normal(q), n);
    auto under = [&](const End& e) {
      if (e.tree_node == UINT32_MAX) return false;
      const ClusterNode& c = tree_.nodes[e.tree_node];
      return tree_.slot[k] >= c.first && tree_.slot[k] < c.first + c.count;
    };
    if ((facing > 0 && under(a)) || (facing < 0 && under(b))) return false;
    Piece c;
    c.n = q.count;
    for (int i = 0; i < q.count; ++i) c.p[size_t(i)] = in_plane(q.v[i]);
    const double s = area(c);
    if (!(std::fabs(s) > 0)) return true;
    if (s < 0) std::reverse(c.p.begin(), c.p.begin() + c.n);
    left.take(c, negligible);
    return !left.overflow;
  };
  // The polygon the ray met first, alone (most walls are one quad), then the others in the plane that
  // overlap R (a walk of the cluster tree).
  if (!cover(first)) return false;
  if (left.pieces.empty()) return true;
  region.lo = region.lo - Vec3(tol, tol, tol);
  region.hi = region.hi + Vec3(tol, tol, tol);
  thread_local std::vector<uint32_t> stack;
  stack.assign(1, 0);
  while (!stack.empty() && !left.pieces.empty()) {
    const ClusterNode& node = tree_.nodes[stack.back()];
    stack.pop_back();
    if (!boxes_overlap(node.bounds, region)) continue;
    if (!node.leaf()) {
      stack.push_back(uint32_t(node.child[1]));
      stack.push_back(uint32_t(node.child[0]));
      continue;
    }
    for (uint32_t s = node.first; s < node.first + node.count && !left.pieces.empty(); ++s) {
      const uint32_t k = tree_.polygons[s];
      if (k == first || !boxes_overlap(tree_.polygon_bounds[k], region)) continue;
      if (!cover(k)) return false;
    }
  }
  double uncovered = 0;
  for (const Piece& piece : left.pieces) uncovered += area(piece);
  return uncovered <= negligible;
}

}  // namespace walkrad
