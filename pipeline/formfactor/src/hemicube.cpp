// Hemicube form factors by scan conversion and a z-buffer (hemicube.h).
#include "walkrad/formfactor/hemicube.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace walkrad {

namespace {


// A face's camera: `forward` from the point to the face's centre, `right` and `up` spanning it.
// The top face sees up/forward in [-1, 1]; a side face only [0, 1] (above the horizon).
struct Face {
  Vec3 right, up, forward;
  bool side;
};

// Delta form factors of the top face (R×R) and of a side face (R × R/2, row 0 at the horizon):
// the same for every point, so kept per thread for the last resolution.
struct DeltaTable {
  int resolution = 0;
  std::vector<double> top, side;
};

const DeltaTable& delta_table(int r) {
  thread_local DeltaTable t;
  if (t.resolution == r) return t;
  t.resolution = r;
  const double step = 2.0 / r, da = step * step;
  t.top.assign(size_t(r) * r, 0.0);
  t.side.assign(size_t(r) * (r / 2), 0.0);
  for (int j = 0; j < r; ++j) {
    for (int i = 0; i < r; ++i) {
      const double x = -1 + (i + 0.5) * step, y = -1 + (j + 0.5) * step, q = x * x + y * y + 1;
      t.top[size_t(j) * r + i] = da / (kPi * q * q);
    }
  }
  for (int j = 0; j < r / 2; ++j) {
    for (int i = 0; i < r; ++i) {
      const double y = -1 + (i + 0.5) * step, z = (j + 0.5) * step, q = y * y + z * z + 1;
      t.side[size_t(j) * r + i] = z * da / (kPi * q * q);
    }
  }
  return t;
}

// Sutherland-Hodgman against dot(c, plane) >= offset, in face coordinates (right, up, forward).
void clip(std::vector<Vec3>& poly, const Vec3& plane, double offset, std::vector<Vec3>& scratch) {
  scratch.clear();
  for (size_t k = 0; k < poly.size(); ++k) {
    const Vec3& a = poly[k];
    const Vec3& b = poly[(k + 1) % poly.size()];
    const double da = dot(a, plane) - offset, db = dot(b, plane) - offset;
    if (da >= 0) scratch.push_back(a);
    if ((da >= 0) != (db >= 0)) scratch.push_back(a + (b - a) * (da / (da - db)));
  }
  poly.swap(scratch);
}

struct Buffers {
  std::vector<double> depth;
  std::vector<int32_t> id;
};

// Draws the polygon (vertices relative to the point) into one face's z-buffer.
void rasterise(const Face& face, int r, const Polygon& poly, int32_t index, const Vec3& p, Buffers& buf,
               std::vector<Vec3>& v, std::vector<Vec3>& scratch) {
  v.clear();
  double reach = 0;
  for (int k = 0; k < poly.count; ++k) {
    const Vec3 d = poly.v[k] - p;
    v.push_back({dot(d, face.right), dot(d, face.up), dot(d, face.forward)});
    reach = std::max(reach, length(d));
  }
  // The frustum: near plane first (the part behind the point would project inverted), then the
  // four sides, so that projected coordinates stay within the face.
  clip(v, {0, 0, 1}, 1e-9 * reach, scratch);
  clip(v, {-1, 0, 1}, 0, scratch);  // right <= forward
  clip(v, {1, 0, 1}, 0, scratch);   // -right <= forward
  clip(v, {0, -1, 1}, 0, scratch);  // up <= forward
  clip(v, face.side ? Vec3(0, 1, 0) : Vec3(0, 1, 1), 0, scratch);  // horizon, or -up <= forward
  if (v.size() < 3) return;

  // The polygon's plane in face coordinates: depth along a pixel's ray (x, y, 1) is e / (m · ray).
  const Vec3 pn = polygon_area_normal(poly);
  const Vec3 m(dot(pn, face.right), dot(pn, face.up), dot(pn, face.forward));
  const double e = dot(poly.v[0] - p, pn);

  const int rows = face.side ? r / 2 : r;
  const double step = 2.0 / r, y_origin = face.side ? 0.0 : -1.0;
  double ymin = INFINITY, ymax = -INFINITY;
  for (Vec3& c : v) {
    c = {c.x / c.z, c.y / c.z, 0.0};  // projected onto the face (forward = 1)
    ymin = std::min(ymin, c.y);
    ymax = std::max(ymax, c.y);
  }
  // Rows whose centre y_c satisfies ymin <= y_c < ymax; columns likewise: a pixel centre on an edge
  // shared by two polygons is drawn once.
  const int j0 = std::max(0, int(std::ceil((ymin - y_origin) / step - 0.5)));
  const int j1 = std::min(rows, int(std::ceil((ymax - y_origin) / step - 0.5)));
  for (int j = j0; j < j1; ++j) {
    const double yc = y_origin + (j + 0.5) * step;
    double xl = INFINITY, xr = -INFINITY;
    for (size_t k = 0; k < v.size(); ++k) {
      const Vec3& a = v[k];
      const Vec3& b = v[(k + 1) % v.size()];
      if ((a.y <= yc) == (b.y <= yc)) continue;  // the edge does not cross this row
      const double x = a.x + (yc - a.y) * (b.x - a.x) / (b.y - a.y);
      xl = std::min(xl, x);
      xr = std::max(xr, x);
    }
    if (!(xl < xr)) continue;
    const int i0 = std::max(0, int(std::ceil((xl + 1) / step - 0.5)));
    const int i1 = std::min(r, int(std::ceil((xr + 1) / step - 0.5)));
    for (int i = i0; i < i1; ++i) {
      const double xc = -1 + (i + 0.5) * step;
      const double den = m.x * xc + m.y * yc + m.z;
      const double t = den != 0 ? std::fabs(e / den) : std::numeric_limits<double>::max();
      const size_t idx = size_t(j) * r + i;
      if (t < buf.depth[idx]) {
        buf.depth[idx] = t;
        buf.id[idx] = index;
      }
    }
  }
}

}  // namespace

std::vector<double> hemicube_form_factors(const Vec3& p, const Vec3& n_in, const std::vector<Polygon>& polygons,
                                          int resolution) {
  std::vector<double> ff(polygons.size(), 0.0);
  const int r = std::max(2, resolution + (resolution & 1));
  const Vec3 n = normalize(n_in);
  // Any tangent frame: the hemicube's result does not depend on its rotation about n beyond aliasing.
  const Vec3 t = normalize(std::fabs(n.x) < 0.9 ? cross(n, Vec3(1, 0, 0)) : cross(n, Vec3(0, 1, 0)));
  const Vec3 b = cross(n, t);
  const Face faces[5] = {{t, b, n, false}, {b, n, t, true}, {-b, n, -t, true}, {-t, n, b, true}, {t, n, -b, true}};

  // Which polygons face the point (and so may receive credit), and which are edge-on (skipped).
  std::vector<char> front(polygons.size(), 0), drawn(polygons.size(), 0);
  for (size_t k = 0; k < polygons.size(); ++k) {
    const Polygon& poly = polygons[k];
    const Vec3 pn = polygon_area_normal(poly);
    double size2 = 0;
    for (int c = 0; c < poly.count; ++c) size2 = std::max(size2, dot(poly.v[c] - p, poly.v[c] - p));
    const double height = dot(p - poly.v[0], pn);
    if (std::fabs(height) <= 1e-12 * length(pn) * std::sqrt(size2)) continue;
    drawn[k] = 1;
    front[k] = height > 0;
  }

  const DeltaTable& delta = delta_table(r);
  Buffers buf;
  std::vector<Vec3> v, scratch;
  for (const Face& face : faces) {
    const size_t pixels = size_t(r) * (face.side ? r / 2 : r);
    buf.depth.assign(pixels, INFINITY);
    buf.id.assign(pixels, -1);
    for (size_t k = 0; k < polygons.size(); ++k)
      if (drawn[k]) rasterise(face, r, polygons[k], int32_t(k), p, buf, v, scratch);
    const std::vector<double>& table = face.side ? delta.side : delta.top;
    for (size_t px = 0; px < pixels; ++px)
      if (buf.id[px] >= 0 && front[size_t(buf.id[px])]) ff[size_t(buf.id[px])] += table[px];
  }
  return ff;
}

}  // namespace walkrad
