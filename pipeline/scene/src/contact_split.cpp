#include "walkrad/scene/contact_split.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "walkrad/scene/cluster_tree.h"
#include "walkrad/scene/convex_loop.h"

namespace walkrad {

namespace {

// A cut: the plane through an edge (a, b) lying on polygon q's plane, perpendicular to q.
struct Cut {
  Vec3 n;
  double d;
  double length;  // of the edge that made it
};

// At most this many cuts per polygon, the lines with the most contact first: a wall's foot matters,
// the thirty books on a shelf board would cut it into slivers for little gain.
constexpr size_t kMaxCutsPerPolygon = 16;

// Where a polygon stands on q: the part of its edge on q's plane inside q, and the way it faces.
struct Standing {
  Vec3 a, b, n;
};

// Edges of polygon p that lie on q's plane and cross q's interior (standing: where they do, when given).
void contact_cuts(const Polygon& q, const Vec3& qn, const Polygon& p, double tol, std::vector<Cut>& cuts,
                  std::vector<Standing>* standing = nullptr) {
  const Vec3 pn = polygon_normal(p);
  if (std::fabs(dot(pn, qn)) > 1 - 1e-9) return;  // coplanar or parallel: no contact line
  for (int k = 0; k < p.count; ++k) {
    const Vec3 a = p.v[k], b = p.v[(k + 1) % p.count];
    if (std::fabs(dot(a - q.v[0], qn)) > tol || std::fabs(dot(b - q.v[0], qn)) > tol) continue;
    const Vec3 dir = b - a;
    if (length(dir) <= tol) continue;
    Cut c;
    c.n = normalize(cross(dir, qn));
    c.d = dot(c.n, a);
    c.length = length(dir);
    // Does the segment [a, b] touch q's interior? Clip it against q's edges.
    double t0 = 0, t1 = 1;
    for (int e = 0; e < q.count && t0 < t1; ++e) {
      const Vec3 inward = cross(qn, q.v[(e + 1) % q.count] - q.v[e]);
      const double s0 = dot(a - q.v[e], inward), s1 = dot(b - q.v[e], inward);
      const double eps = tol * length(inward);
      if (s0 < eps && s1 < eps) { t1 = t0; break; }
      if (s0 < eps) t0 = std::max(t0, (eps - s0) / (s1 - s0));
      if (s1 < eps) t1 = std::min(t1, (eps - s0) / (s1 - s0));
    }
    if (t1 - t0 > 1e-9) {
      cuts.push_back(c);
      if (standing) standing->push_back({a + dir * t0, a + dir * t1, pn});
    }
  }
}

// Whether a piece is enclosed by what stands on it: some polygon stands along one of its edges with
// its back to the piece, and none along any of its edges faces it (the floor under a box that has no
// bottom face, a shelf board under a book). Its corners are dark; the lit piece beside it must not
// average them in (office-floor: otherwise a sample point 5 mm in front of a row of books is 43% too
// dark, the outline's vertices taking the larger piece under the books).
bool enclosed(const Loop& l, const Vec3& centre, const std::vector<Standing>& standing, double tol) {
  bool behind = false;
  for (const Standing& s : standing) {
    const Vec3 along = s.b - s.a;
    const double len = length(along);
    if (len <= tol) continue;
    const Vec3 u = along / len;
    for (size_t k = 0; k < l.size(); ++k) {
      const Vec3 e0 = l[k], e1 = l[(k + 1) % l.size()];
      // The edge on the segment's line, and overlapping it by more than the tolerance.
      const Vec3 r0 = e0 - s.a, r1 = e1 - s.a;
      if (length(r0 - u * dot(r0, u)) > tol || length(r1 - u * dot(r1, u)) > tol) continue;
      const double lo = std::max(0.0, std::min(dot(r0, u), dot(r1, u))), hi = std::min(len, std::max(dot(r0, u), dot(r1, u)));
      if (hi - lo <= tol) continue;
      if (dot(centre - s.a, s.n) > 0) return false;  // something stands facing the piece: it is open
      behind = true;
    }
  }
  return behind;
}

// A cover: polygon p parallel to q, in front of it within kCoverGap of the smaller one's size (a lamp
// hung just under a ceiling, a box resting a hair above a floor). The strip of q under p is dark and
// seen by nothing; its corners must not be averaged with the lit ones around it.
constexpr double kCoverGap = 0.02;

// p's corners projected on q's plane, when p covers q (else empty); gap: p's height over q.
Loop cover_footprint(const Polygon& q, const Vec3& qn, const Polygon& p, double tol, double* gap_out = nullptr) {
  const Vec3 pn = polygon_normal(p);
  if (std::fabs(dot(pn, qn)) < 1 - 1e-6) return {};
  const double gap = dot(p.v[0] - q.v[0], qn);
  if (gap_out) *gap_out = gap;
  const double size = std::sqrt(std::min(polygon_area(p), polygon_area(q)));
  if (gap <= tol || gap > kCoverGap * size) return {};
  Loop out;
  for (int k = 0; k < p.count; ++k) out.push_back(p.v[k] - qn * dot(p.v[k] - q.v[0], qn));
  if (dot(pn, qn) < 0) std::reverse(out.begin(), out.end());  // counter-clockwise seen along qn
  return out;
}

// Cuts along a cover's footprint edges that cross q's interior.
void cover_cuts(const Polygon& q, const Vec3& qn, const Loop& footprint, double tol, std::vector<Cut>& cuts) {
  for (size_t k = 0; k < footprint.size(); ++k) {
    // The edge as a triangle standing on q's plane, handed to contact_cuts.
    Polygon e;
    e.count = 3;
    const Vec3 a = footprint[k], b = footprint[(k + 1) % footprint.size()];
    e.v = {a, b, b + qn * (10 * tol + length(b - a)), Vec3{}};
    const size_t before = cuts.size();
    contact_cuts(q, qn, e, tol, cuts);
    // Keep only the cut made by the edge (a, b) itself.
    for (size_t c = before; c < cuts.size();)
      if (std::fabs(dot(cuts[c].n, a) - cuts[c].d) <= tol && std::fabs(dot(cuts[c].n, b) - cuts[c].d) <= tol) ++c;
      else cuts.erase(cuts.begin() + long(c));
  }
}

// q's bounds grown by the gap a cover may leave (kCoverGap of q's size; the test in cover_footprint is
// against the smaller of the two).
Bounds reach_of(const Polygon& q, double tol) {
  Bounds qb = polygon_bounds(q);
  const double reach = std::max(tol, kCoverGap * std::sqrt(polygon_area(q)));
  qb.extend(qb.lo - Vec3(reach, reach, reach));
  qb.extend(qb.hi + Vec3(reach, reach, reach));
  return qb;
}

// Calls f(p) for every polygon p other than qi whose bounds touch qb (a tree query), in tree order:
// deterministic.
template <class F>
void for_each_near(const ClusterTree& tree, const Scene& scene, uint32_t qi, const Bounds& qb, std::vector<int32_t>& stack, F&& f) {
  stack.assign(1, 0);
  while (!stack.empty() && !tree.nodes.empty()) {
    const ClusterNode& node = tree.nodes[size_t(stack.back())];
    stack.pop_back();
    const Bounds& b = node.bounds;
    if (b.hi.x < qb.lo.x || b.lo.x > qb.hi.x || b.hi.y < qb.lo.y || b.lo.y > qb.hi.y || b.hi.z < qb.lo.z || b.lo.z > qb.hi.z) continue;
    if (!node.leaf()) { stack.push_back(node.child[1]); stack.push_back(node.child[0]); continue; }
    for (uint32_t i = node.first; i < node.first + node.count; ++i)
      if (tree.polygons[i] != qi) f(scene.polygons[tree.polygons[i]]);
  }
}

bool inside(const Loop& footprint, const Vec3& normal, const Vec3& x) {
  for (size_t k = 0; k < footprint.size(); ++k)
    if (dot(cross(footprint[(k + 1) % footprint.size()] - footprint[k], x - footprint[k]), normal) <= 0) return false;
  return true;
}

// One polygon's pieces (empty: the polygon whole), whether each lies under a cover, and the cuts applied.
struct Split {
  std::vector<Loop> pieces;
  std::vector<uint8_t> under;
  uint64_t applied = 0;
};
struct Scratch {
  std::vector<Cut> cuts, unique;
  std::vector<Loop> covers, next;
  std::vector<Standing> standing;
  std::vector<int32_t> stack;
};

// Polygon qi cut along the contacts and covers of the polygons near it (its own affair: any thread).
void split_polygon(const Scene& scene, const ClusterTree& tree, uint32_t qi, double tol, Scratch& w, Split& out_q) {
  std::vector<Cut>& cuts = w.cuts;
  std::vector<Loop>& covers = w.covers;
  std::vector<Standing>& standing = w.standing;
  const Polygon& q = scene.polygons[qi];
  const Vec3 qn = polygon_normal(q);
  const Bounds qb = reach_of(q, tol);
  cuts.clear();
  covers.clear();
  standing.clear();
  for_each_near(tree, scene, qi, qb, w.stack, [&](const Polygon& p) {
    contact_cuts(q, qn, p, tol, cuts, &standing);
    Loop footprint = cover_footprint(q, qn, p, tol);
    if (!footprint.empty()) {
      cover_cuts(q, qn, footprint, tol, cuts);
      covers.push_back(std::move(footprint));
    }
  });
  if (cuts.empty() && covers.empty()) return;
  // One cut per line (collinear edges: a row of books, two boxes side by side), the most contact
  // along it first: a row of books' fronts (a metre of contact on one line, where the books' strip
  // in front of them is lit and the board under them dark) before any one book's side.
  for (Cut& c : cuts)
    if (c.n.x < 0 || (c.n.x == 0 && (c.n.y < 0 || (c.n.y == 0 && c.n.z < 0)))) { c.n = -c.n; c.d = -c.d; }
  std::vector<Cut>& unique = w.unique;
  unique.clear();
  for (const Cut& c : cuts) {
    bool same = false;
    for (Cut& u : unique)
      if (!same && dot(c.n, u.n) > 1 - 1e-12 && std::fabs(c.d - u.d) <= tol) {
        u.length += c.length;
        same = true;
      }
    if (!same) unique.push_back(c);
  }
  // Lengths compared in steps of the tolerance, ties kept in discovery order (tree order): edges of
  // equal length (a square box's feet) differ in their last bits once the scene is scaled or moved,
  // and must not swap (the pieces, their order and thus the bake would change; docs/numerics.md).
  std::stable_sort(unique.begin(), unique.end(),
                   [&](const Cut& a, const Cut& b) { return std::llround(a.length / tol) > std::llround(b.length / tol); });
  if (unique.size() > kMaxCutsPerPolygon) unique.resize(kMaxCutsPerPolygon);
  std::vector<Loop> pieces = {Loop(q.v.begin(), q.v.begin() + q.count)};
  std::vector<Loop>& next = w.next;
  Loop below, above;
  const double min_area = tol * std::sqrt(polygon_area(q));  // no sliver thinner than the tolerance
  for (const Cut& c : unique) {
    next.clear();
    for (const Loop& l : pieces) {
      split_loop(l, c.n, c.d, below, above);
      if (below.size() >= 3 && above.size() >= 3 && loop_area(below) > min_area && loop_area(above) > min_area) {
        next.push_back(below);
        next.push_back(above);
        ++out_q.applied;
      } else {
        next.push_back(l);
      }
    }
    pieces.swap(next);
  }
  // A piece under a cover, or enclosed by what stands on it, takes a copy of its material: the
  // same surface, its own smoothing group (the mesher averages vertices only within a material).
  for (const Loop& l : pieces) {
    Vec3 centre;
    for (const Vec3& v : l) centre += v / double(l.size());
    bool under = false;
    for (const Loop& f : covers) under = under || inside(f, qn, centre);
    out_q.under.push_back(under || enclosed(l, centre, standing, tol));
  }
  out_q.pieces = std::move(pieces);
}

}  // namespace

Scene split_contacts(const Scene& scene, ContactSplitStats& stats, double tolerance) {
  Scene out = scene;
  out.polygons.clear();
  const Bounds bounds = scene.bounds();
  const double diag = length(bounds.diagonal());
  const double tol = tolerance > 0 ? tolerance : 1e-6 * diag;
  const ClusterTree tree = build_cluster_tree(scene);

  // Each polygon's pieces are its own affair: found in parallel, then given out in polygon order
  // (materials for covered pieces made as they are first needed), so the scene is the same whatever
  // the threads.
  std::vector<Split> split(scene.polygons.size());
  tbb::enumerable_thread_specific<Scratch> scratch;
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(scene.polygons.size()), 64), [&](const tbb::blocked_range<uint32_t>& r) {
    Scratch& w = scratch.local();
    for (uint32_t qi = r.begin(); qi != r.end(); ++qi) split_polygon(scene, tree, qi, tol, w, split[qi]);
  });

  std::vector<int32_t> covered_material(scene.materials.size(), -1);  // q's material → its covered copy
  for (uint32_t qi = 0; qi < scene.polygons.size(); ++qi) {
    const Polygon& q = scene.polygons[qi];
    Split& sq = split[qi];
    if (sq.pieces.empty()) {
      out.polygons.push_back(q);
      continue;
    }
    if (sq.applied) {
      ++stats.polygons_split;
      stats.cuts += sq.applied;
    }
    for (size_t k = 0; k < sq.pieces.size(); ++k) {
      Polygon like = q;
      if (sq.under[k]) {
        int32_t& m = covered_material[q.material];
        if (m < 0) {
          out.materials.push_back(scene.materials[q.material]);
          out.materials.back().name += " (covered)";
          m = int32_t(out.materials.size() - 1);
        }
        like.material = uint32_t(m);
        ++stats.covered;
      }
      emit_loop(sq.pieces[k], like, out.polygons);
    }
    sq = Split{};
  }
  return out;
}

std::vector<std::vector<ContactBand>> contact_bands(const Scene& scene, const ClusterTree& tree, const std::vector<uint8_t>& wanted,
                                                    double tolerance) {
  std::vector<std::vector<ContactBand>> out(scene.polygons.size());
  const double tol = tolerance > 0 ? tolerance : 1e-6 * length(scene.bounds().diagonal());
  std::vector<int32_t> stack;
  std::vector<Loop> covers;
  std::vector<double> gaps;
  for (uint32_t qi = 0; qi < scene.polygons.size(); ++qi) {
    if (qi >= wanted.size() || !wanted[qi]) continue;
    const Polygon& q = scene.polygons[qi];
    const Vec3 qn = polygon_normal(q);
    covers.clear();
    gaps.clear();
    for_each_near(tree, scene, qi, reach_of(q, tol), stack, [&](const Polygon& p) {
      double gap = 0;
      Loop footprint = cover_footprint(q, qn, p, tol, &gap);
      if (footprint.empty()) return;
      covers.push_back(std::move(footprint));
      gaps.push_back(gap);
    });
    for (size_t c = 0; c < covers.size(); ++c) {
      const Loop& footprint = covers[c];
      const double w = kContactBand * gaps[c];
      for (size_t k = 0; k < footprint.size(); ++k) {
        // The edge moved out by w and lengthened by w at either end: a rectangle's grown outline.
        const Vec3 a = footprint[k], b = footprint[(k + 1) % footprint.size()];
        const double len = length(b - a);
        if (len <= tol) continue;
        const Vec3 along = (b - a) / len, away = cross(along, qn);
        const Vec3 a2 = a + (away - along) * w, b2 = b + (away + along) * w;
        double t0 = 0, t1 = 1;
        if (!clip_segment(q.v.data(), size_t(q.count), qn, a2, b2, t0, t1) || (t1 - t0) * (len + 2 * w) <= tol) continue;
        const ContactBand band{a2 + (b2 - a2) * t0, a2 + (b2 - a2) * t1};
        // Not where another cover lies over it: the underside of a box beside the floor piece around it
        // is covered by the piece under the box, and is no outline's surroundings.
        bool covered = false;
        for (const Loop& f : covers) covered = covered || inside(f, qn, (band.a + band.b) * 0.5);
        if (!covered) out[qi].push_back(band);
      }
    }
  }
  return out;
}

}  // namespace walkrad
