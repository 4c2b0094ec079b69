// find_openings (openings.h): per plane, the convex hull of the polygons' union less the union
// (Clipper, Vatti's clipping), then each piece cut into triangles by ear clipping.
#include "walkrad/scene/openings.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include <polyclipping/clipper.hpp>

#include "walkrad/core/sampling.h"

namespace walkrad {

namespace {

namespace cl = ClipperLib;

// A polygon's plane with its normal turned so that its largest component is positive: both faces of a
// wall, and a wall's two polygons back to back, fall in one plane.
struct Plane {
  Vec3 n;
  double d;
};
Plane unoriented_plane(const Polygon& p) {
  Vec3 n = polygon_normal(p);
  const int axis = std::fabs(n.x) >= std::fabs(n.y) && std::fabs(n.x) >= std::fabs(n.z) ? 0 : std::fabs(n.y) >= std::fabs(n.z) ? 1 : 2;
  if (n[axis] < 0) n = -n;
  return {n, dot(n, p.v[0])};
}

cl::cInt cross(const cl::IntPoint& o, const cl::IntPoint& a, const cl::IntPoint& b) {
  return (a.X - o.X) * (b.Y - o.Y) - (a.Y - o.Y) * (b.X - o.X);
}

// Andrew's monotone chain: counter-clockwise, no collinear points.
cl::Path convex_hull(cl::Path points) {
  std::sort(points.begin(), points.end(), [](const cl::IntPoint& a, const cl::IntPoint& b) { return a.X < b.X || (a.X == b.X && a.Y < b.Y); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return {};
  cl::Path hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i - 1]) <= 0) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

// Ear clipping of a simple counter-clockwise polygon (Meisters 1975): O(n²), openings have few corners.
std::vector<std::array<size_t, 3>> ear_clip(const cl::Path& p) {
  std::vector<std::array<size_t, 3>> out;
  std::vector<size_t> left(p.size());
  for (size_t k = 0; k < p.size(); ++k) left[k] = k;
  const auto inside = [&](const cl::IntPoint& a, const cl::IntPoint& b, const cl::IntPoint& c, const cl::IntPoint& x) {
    return cross(a, b, x) >= 0 && cross(b, c, x) >= 0 && cross(c, a, x) >= 0;
  };
  size_t guard = 0;
  while (left.size() > 3 && guard < 4 * p.size() * p.size()) {
    bool cut = false;
    for (size_t k = 0; k < left.size() && !cut; ++k, ++guard) {
      const size_t a = left[(k + left.size() - 1) % left.size()], b = left[k], c = left[(k + 1) % left.size()];
      if (cross(p[a], p[b], p[c]) <= 0) continue;  // reflex or flat: no ear
      bool empty = true;
      for (size_t q : left)
        if (q != a && q != b && q != c && inside(p[a], p[b], p[c], p[q])) empty = false;
      if (!empty) continue;
      out.push_back({a, b, c});
      left.erase(left.begin() + std::ptrdiff_t(k));
      cut = true;
    }
    if (!cut) break;  // not simple after all: what is cut so far
  }
  if (left.size() == 3 && cross(p[left[0]], p[left[1]], p[left[2]]) > 0) out.push_back({left[0], left[1], left[2]});
  return out;
}

}  // namespace

std::vector<Opening> find_openings(const Scene& scene) {
  std::vector<Opening> out;
  const double diagonal = length(scene.bounds().diagonal());
  if (!(diagonal > 0)) return out;
  const double width = kOpeningWidth * diagonal;
  // Planes within 1e-5 in normal and width / 10 in offset are one.
  std::map<std::array<int64_t, 4>, std::vector<uint32_t>> planes;
  for (uint32_t i = 0; i < scene.polygons.size(); ++i) {
    if (!(polygon_area(scene.polygons[i]) > 0)) continue;
    const Plane pl = unoriented_plane(scene.polygons[i]);
    planes[{std::llround(pl.n.x * 1e5), std::llround(pl.n.y * 1e5), std::llround(pl.n.z * 1e5), std::llround(pl.d * 10 / width)}].push_back(i);
  }
  for (const auto& [key, members] : planes) {
    if (members.size() < 2) continue;  // one convex polygon: its hull is itself
    const Plane pl = unoriented_plane(scene.polygons[members[0]]);
    Vec3 t, s;
    frame(pl.n, t, s);
    Bounds b;
    for (uint32_t i : members)
      for (int k = 0; k < scene.polygons[i].count; ++k) b.extend(scene.polygons[i].v[k]);
    const Vec3 centre = (b.lo + b.hi) * 0.5;
    const double extent = std::max(length(b.diagonal()), width);
    const double scale = double(int64_t(1) << 30) / extent;  // 2⁻³⁰ of the plane's extent; products stay within 2⁶²
    cl::Paths polygons;
    cl::Path corners;
    for (uint32_t i : members) {
      const Polygon& p = scene.polygons[i];
      cl::Path path;
      for (int k = 0; k < p.count; ++k) {
        const Vec3 r = p.v[k] - centre;
        path.push_back({cl::cInt(std::llround(dot(r, t) * scale)), cl::cInt(std::llround(dot(r, s) * scale))});
      }
      if (!cl::Orientation(path)) cl::ReversePath(path);  // either face: counted once
      corners.insert(corners.end(), path.begin(), path.end());
      polygons.push_back(std::move(path));
    }
    cl::Paths united;
    cl::Clipper u;
    u.AddPaths(polygons, cl::ptSubject, true);
    u.Execute(cl::ctUnion, united, cl::pftNonZero, cl::pftNonZero);
    const cl::Path hull = convex_hull(corners);
    if (hull.empty()) continue;
    cl::Paths pieces;
    cl::Clipper d;
    d.AddPath(hull, cl::ptSubject, true);
    d.AddPaths(united, cl::ptClip, true);
    d.Execute(cl::ctDifference, pieces, cl::pftNonZero, cl::pftNonZero);
    const double plane_d = dot(centre, pl.n);
    for (cl::Path& piece : pieces) {
      cl::CleanPolygon(piece, width * scale / 10);
      if (piece.size() < 3 || !cl::Orientation(piece)) continue;  // holes in a piece are kept as part of it
      const double area = cl::Area(piece) / (scale * scale);
      double perimeter = 0;
      for (size_t k = 0; k < piece.size(); ++k) {
        const cl::IntPoint& a = piece[k];
        const cl::IntPoint& c = piece[(k + 1) % piece.size()];
        perimeter += std::hypot(double(c.X - a.X), double(c.Y - a.Y)) / scale;
      }
      if (2 * area < width * perimeter) continue;  // a crack, not an opening
      Opening o;
      o.normal = pl.n;
      o.area = area;
      const auto at = [&](const cl::IntPoint& q) {
        return centre + pl.n * (pl.d - plane_d) + t * (double(q.X) / scale) + s * (double(q.Y) / scale);
      };
      for (const auto& tri : ear_clip(piece)) {
        Polygon p;
        p.count = 3;
        p.v = {at(piece[tri[0]]), at(piece[tri[1]]), at(piece[tri[2]]), {}};
        o.triangles.push_back(p);
      }
      if (!o.triangles.empty()) out.push_back(std::move(o));
    }
  }
  return out;
}

}  // namespace walkrad
