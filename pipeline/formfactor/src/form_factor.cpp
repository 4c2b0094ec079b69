// Form factors by Lambert's contour formula (form_factor.h).
#include "walkrad/formfactor/form_factor.h"
#include "walkrad/core/rounding.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace walkrad {

namespace {


// Gauss-Legendre abscissae and weights on [0, 1], orders 1..8.
struct GaussRule {
  std::array<double, 8> x, w;
};

GaussRule make_gauss_rule(int order) {
  // Nodes and weights on [-1, 1] (Abramowitz & Stegun, table 25.4), mapped to [0, 1].
  static const std::vector<std::vector<std::pair<double, double>>> table = {
      {{0.0, 2.0}},
      {{-0.5773502691896257, 1.0}, {0.5773502691896257, 1.0}},
      {{-0.7745966692414834, 0.5555555555555556}, {0.0, 0.8888888888888888}, {0.7745966692414834, 0.5555555555555556}},
      {{-0.8611363115940526, 0.3478548451374538}, {-0.3399810435848563, 0.6521451548625461},
       {0.3399810435848563, 0.6521451548625461}, {0.8611363115940526, 0.3478548451374538}},
      {{-0.9061798459386640, 0.2369268850561891}, {-0.5384693101056831, 0.4786286704993665}, {0.0, 0.5688888888888889},
       {0.5384693101056831, 0.4786286704993665}, {0.9061798459386640, 0.2369268850561891}},
      {{-0.9324695142031521, 0.1713244923791704}, {-0.6612093864662645, 0.3607615730481386},
       {-0.2386191860831969, 0.4679139345726910}, {0.2386191860831969, 0.4679139345726910},
       {0.6612093864662645, 0.3607615730481386}, {0.9324695142031521, 0.1713244923791704}},
      {{-0.9491079123427585, 0.1294849661688697}, {-0.7415311855993945, 0.2797053914892766},
       {-0.4058451513773972, 0.3818300505051189}, {0.0, 0.4179591836734694}, {0.4058451513773972, 0.3818300505051189},
       {0.7415311855993945, 0.2797053914892766}, {0.9491079123427585, 0.1294849661688697}},
      {{-0.9602898564975363, 0.1012285362903763}, {-0.7966664774136267, 0.2223810344533745},
       {-0.5255324099163290, 0.3137066458778873}, {-0.1834346424956498, 0.3626837833783620},
       {0.1834346424956498, 0.3626837833783620}, {0.5255324099163290, 0.3137066458778873},
       {0.7966664774136267, 0.2223810344533745}, {0.9602898564975363, 0.1012285362903763}},
  };
  GaussRule r{};
  const auto& row = table[std::clamp(order, 1, 8) - 1];
  for (size_t i = 0; i < row.size(); ++i) {
    r.x[i] = 0.5 * (row[i].first + 1.0);
    r.w[i] = 0.5 * row[i].second;
  }
  return r;
}

// The eight rules, mapped once (the same arithmetic as mapping them at every call: the same bits).
const GaussRule& gauss_rule(int order) {
  static const std::array<GaussRule, 8> rules = [] {
    std::array<GaussRule, 8> r{};
    for (int k = 0; k < 8; ++k) r[size_t(k)] = make_gauss_rule(k + 1);
    return r;
  }();
  return rules[size_t(std::clamp(order, 1, 8) - 1)];
}

// atan(t) for |t| <= 0.66: t + t·z·P(z)/Q(z), z = t², the rational approximation of Cephes' atan
// (S. L. Moshier, "Methods and Programs for Mathematical Functions", 1989), within 2.2e-16 relative.
double atan_core(double t) {
  const double z = t * t;
  const double p = (((-8.750608600031904122785e-1 * z - 1.615753718733365076637e1) * z - 7.500855792314704667340e1) * z -
                    1.228866684490136173410e2) * z - 6.485021904942025371773e1;
  const double q = ((((z + 2.485846490142306297962e1) * z + 1.650270098316988542046e2) * z + 4.328810604912902668951e2) * z +
                    4.853903996359136964868e2) * z + 1.945506571482613964425e2;
  return t + t * (z * p / q);
}

// Inlined into the contour formula's loop; vector_angle is the same for callers elsewhere.
inline double angle_of(double s, double c) {
  const double a = std::fabs(c);
  double angle;
  if (s > 2.414213562373095 * a) angle = 0.5 * kPi - atan_core(a / s);         // beyond 3π/8
  else if (s > 0.66 * a) angle = 0.25 * kPi + atan_core((s - a) / (s + a));  // π/4 ± π/8
  else angle = a > 0 ? atan_core(s / a) : 0.0;  // two zero vectors: 0, not NaN
  return c < 0 ? kPi - angle : angle;
}

}  // namespace

double vector_angle(double s, double c) { return angle_of(s, c); }

ClippedPolygon clip_to_hemisphere(const Vec3& p, const Vec3& n, const Vec3* v, int count) {
  // Sutherland-Hodgman against one plane.
  ClippedPolygon out;
  count = std::min(count, 4);
  for (int k = 0; k < count; ++k) {
    const Vec3& a = v[k];
    const Vec3& b = v[(k + 1) % count];
    const double da = dot(a - p, n), db = dot(b - p, n);
    if (da >= 0) out.v[size_t(out.count++)] = a;
    if ((da >= 0) != (db >= 0)) out.v[size_t(out.count++)] = a + (b - a) * (da / (da - db));
  }
  return out;
}

ContourSource::ContourSource(const Polygon& p)
    : poly(p), area_normal(polygon_area_normal(p)), norm(length(area_normal)), root_norm(std::sqrt(norm)) {}

double point_to_polygon(const Vec3& p, const Vec3& n, const Polygon& poly) { return point_to_polygon(p, n, ContourSource(poly)); }

double point_to_polygon(const Vec3& p, const Vec3& n, const ContourSource& source) {
  const Polygon& poly = source.poly;
  const double plane_distance = dot(p - poly.v[0], source.area_normal);
  // On the source's plane (within 1e-12 of its size, or rounding): the polygon subtends no solid
  // angle (and the formula would mix ±β).
  const double pl = source.norm;
  if (std::fabs(plane_distance) <= pl * (1e-12 * source.root_norm + rounding_at(p))) return 0.0;

  // The corners relative to p, as plain doubles (a Vec3 array would be zeroed on every call): the
  // polygon's own when it lies wholly above p's horizon, the clipped polygon's otherwise.
  const int count = std::min(int(poly.count), 4);
  bool above = true;
  for (int k = 0; k < count; ++k) above = above && dot(poly.v[size_t(k)] - p, n) >= 0;
  double rx[8], ry[8], rz[8];
  int m = 0;
  if (above) {
    for (; m < count; ++m) {
      const Vec3 r = poly.v[size_t(m)] - p;
      rx[m] = r.x, ry[m] = r.y, rz[m] = r.z;
    }
  } else {
    const ClippedPolygon v = clip_to_hemisphere(p, n, poly.v.data(), poly.count);
    for (; m < v.count; ++m) {
      const Vec3 r = v.v[size_t(m)] - p;
      rx[m] = r.x, ry[m] = r.y, rz[m] = r.z;
    }
  }
  if (m < 3) return 0.0;
  // One edge at a time: two at a time (SSE2) gives the same bits and no speed.
  double sum = 0.0;
  for (int k = 0; k < m; ++k) {
    const int j = k + 1 == m ? 0 : k + 1;
    const Vec3 r0{rx[k], ry[k], rz[k]}, r1{rx[j], ry[j], rz[j]};
    const Vec3 c = cross(r0, r1);
    const double cl = length(c);
    if (cl <= 0) continue;  // p on the edge's line: the edge subtends no angle
    const double beta = angle_of(cl, dot(r0, r1));
    sum += beta * dot(n, c) / cl;
  }
  // The sign of the sum follows the winding seen from p; the form factor is its magnitude.
  return std::fabs(sum) / (2.0 * kPi);
}

QuadraturePoints quadrature_points(const Polygon& r, int order) {
  const GaussRule& g = gauss_rule(order);
  order = std::clamp(order, 1, 8);
  const Vec3 v0 = r.v[0], v1 = r.v[1], v2 = r.v[2], v3 = r.count == 4 ? r.v[3] : r.v[2];
  QuadraturePoints pts;
  for (int a = 0; a < order; ++a) {
    for (int b = 0; b < order; ++b) {
      const double s = g.x[a], t = g.x[b];
      // Bilinear map of the unit square; for a triangle v3 = v2 collapses the edge t = 1.
      const Vec3 pos = v0 * ((1 - s) * (1 - t)) + v1 * (s * (1 - t)) + v2 * (s * t) + v3 * ((1 - s) * t);
      const Vec3 ds = (v1 - v0) * (1 - t) + (v2 - v3) * t;
      const Vec3 dt = (v3 - v0) * (1 - s) + (v2 - v1) * s;
      pts.point[pts.count++] = {pos.x, pos.y, pos.z, g.w[a] * g.w[b] * length(cross(ds, dt))};
    }
  }
  return pts;
}

int quadrature_order(double distance, double receiver_size, double source_size) {
  const double ratio = distance / std::max(receiver_size, source_size);
  if (clearly_greater(ratio, 4.0)) return 2;
  if (clearly_greater(ratio, 2.0)) return 3;
  if (clearly_greater(ratio, 1.0)) return 4;
  return 8;
}

ElementEnd::ElementEnd(const Polygon& p)
    : poly(p), normal(polygon_normal(p)), centroid(polygon_centroid(p)), area(polygon_area(p)), size(std::sqrt(area)),
      contour(p) {}

const QuadraturePoints& ReceiverPoints::of_order(int order) {
  const size_t k = size_t(std::clamp(order, 1, 8) - 1);
  if (!have_[k]) {
    points_[k] = quadrature_points(receiver_, order);
    have_[k] = true;
  }
  return points_[k];
}

double element_to_element(const ElementEnd& receiver, const ElementEnd& source, ReceiverPoints& points) {
  if (receiver.area <= 0) return 0.0;
  const double distance = length(receiver.centroid - source.centroid);
  const int order = quadrature_order(distance, receiver.size, source.size);
  double sum = 0.0;
  for (const QuadraturePoint& q : points.of_order(order)) {
    if (dot(q.position - source.poly.v[0], source.normal) <= 0) continue;  // behind the source: sees its back
    sum += q.weight * point_to_polygon(q.position, receiver.normal, source.contour);
  }
  return sum / receiver.area;
}

double element_to_element(const Polygon& receiver, const Polygon& source) {
  const ElementEnd r(receiver), s(source);
  ReceiverPoints points(receiver);
  return element_to_element(r, s, points);
}

}  // namespace walkrad
