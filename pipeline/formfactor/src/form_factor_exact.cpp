// Exact polygon-to-polygon form factor by the double contour integral (form_factor_exact.h).
//
//   A_i F_ij = (1/2π) Σ_k Σ_l (d_k · d_l) ∫_0^{L_k} ∫_0^{L_l} ln |x_k(s) − y_l(t)| dt ds
// over the edges x_k(s) = a_k + d_k s of i and y_l(t) = b_l + d_l t of j (d unit, L the length).
// Stokes' theorem turns the area integral of cosθ_i cosθ_j / (π r²) into this form only while every
// point of each polygon lies in front of the other's plane; outside that the contour formula counts
// the back sides with a negative sign. So both polygons are first clipped to the other's front
// half-space, which is exact: the kernel is zero everywhere that clipping removes.
#include "walkrad/formfactor/form_factor_exact.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace walkrad {

namespace {


struct Edge {
  Vec3 a, d;  // start and unit direction
  double length;
};

// Sutherland-Hodgman against dot(x - o, n) >= 0. Distances within eps of the plane snap to it, so
// a vertex on the plane (a shared edge) neither survives as a sliver nor spawns a duplicate.
std::vector<Vec3> clip(const std::vector<Vec3>& v, const Vec3& o, const Vec3& n, double eps) {
  std::vector<double> dist(v.size());
  for (size_t k = 0; k < v.size(); ++k) {
    const double d = dot(v[k] - o, n);
    dist[k] = std::fabs(d) <= eps ? 0.0 : d;
  }
  std::vector<Vec3> out;
  for (size_t k = 0; k < v.size(); ++k) {
    const size_t m = (k + 1) % v.size();
    if (dist[k] >= 0) out.push_back(v[k]);
    if ((dist[k] > 0 && dist[m] < 0) || (dist[k] < 0 && dist[m] > 0))
      out.push_back(v[k] + (v[m] - v[k]) * (dist[k] / (dist[k] - dist[m])));
  }
  return out;
}

// An antiderivative in u of ln sqrt(u² + h²) (h >= 0), finite at u = h = 0.
double log_antiderivative(double u, double h) {
  const double q = u * u + h * h;
  const double u_ln_r = q > 0 ? 0.5 * u * std::log(q) : 0.0;
  return u_ln_r - u + h * std::atan2(u, h);
}

// ∫_0^L ln |x − (b + d t)| dt in closed form: t0 is x's foot on the line, h its distance from it.
double edge_log_integral(const Vec3& x, const Edge& e) {
  const Vec3 w = x - e.a;
  const double t0 = dot(w, e.d);
  const double h = length(w - e.d * t0);  // not sqrt(|w|² − t0²): that loses half the digits
  return log_antiderivative(e.length - t0, h) - log_antiderivative(-t0, h);
}

// Gauss-Kronrod 7/15 on [0, 1] (Piessens et al. 1983, QUADPACK qk15), nodes symmetric about 1/2.
constexpr double kXgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                            0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                            0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                            0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                            0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                            0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                            0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

// ∫_a^b f by bisection until Kronrod and Gauss agree within tol. Where the integrand has a log
// singularity at an end (edges meeting there) the bisection homes in on it: each level quarters the
// error of the end interval while its share of the tolerance only halves. A difference at the level
// of rounding (QUADPACK's 50 ε ∫|f|) also stops it, so a tolerance below what doubles can resolve
// costs a few levels, not an exponential descent.
template <class F>
double adaptive_gk15(const F& f, double a, double b, double tol, int depth) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double kronrod = fc * kWgk[7], gauss = fc * kWg[3], magnitude = std::fabs(fc) * kWgk[7];
  for (int i = 0; i < 7; ++i) {
    const double f0 = f(c - h * kXgk[i]), f1 = f(c + h * kXgk[i]);
    kronrod += kWgk[i] * (f0 + f1);
    magnitude += kWgk[i] * (std::fabs(f0) + std::fabs(f1));
    if (i % 2 == 1) gauss += kWg[i / 2] * (f0 + f1);
  }
  kronrod *= h;
  gauss *= h;
  const double error = std::fabs(kronrod - gauss);
  if (error <= tol || error <= 50 * 2.2e-16 * h * magnitude || depth >= 40 || !std::isfinite(error)) return kronrod;
  return adaptive_gk15(f, a, c, 0.5 * tol, depth + 1) + adaptive_gk15(f, c, b, 0.5 * tol, depth + 1);
}

// (d_k · d_l) ∫_0^{L_k} ∫_0^{L_l} ln r dt ds for one pair of edges, within tol.
double edge_pair(const Edge& ek, const Edge& el, double tol) {
  const double b = dot(ek.d, el.d);
  if (b == 0) return 0.0;  // perpendicular edges contribute nothing
  tol /= std::fabs(b);
  // The outer integrand is smooth except where x_k(s) meets segment l: at the lines' closest
  // approach, and (collinear edges) where x_k(s) passes l's end points. Split there so that every
  // singularity sits at the end of an interval, where adaptive bisection resolves it.
  std::vector<double> split = {0.0, ek.length};
  const Vec3 w0 = ek.a - el.a;
  const double c = dot(w0, el.d);  // t0(s) = c + b s
  for (double t : {0.0, el.length}) split.push_back((t - c) / b);
  const double parallel = 1.0 - b * b;
  if (parallel > 1e-12) split.push_back((b * dot(el.d, w0) - dot(ek.d, w0)) / parallel);
  std::sort(split.begin(), split.end());
  const auto inner = [&](double s) { return edge_log_integral(ek.a + ek.d * s, el); };
  double sum = 0.0;
  const double margin = 1e-13 * ek.length;
  double prev = 0.0;
  for (double s : split) {
    s = std::clamp(s, 0.0, ek.length);
    if (s - prev <= margin) continue;
    sum += adaptive_gk15(inner, prev, s, tol * (s - prev) / ek.length, 0);
    prev = s;
  }
  return b * sum;
}

std::vector<Edge> edges_of(const std::vector<Vec3>& v, double min_length) {
  std::vector<Edge> edges;
  for (size_t k = 0; k < v.size(); ++k) {
    const Vec3 d = v[(k + 1) % v.size()] - v[k];
    const double l = length(d);
    if (l > min_length) edges.push_back({v[k], d / l, l});
  }
  return edges;
}

}  // namespace

double polygon_to_polygon_exact(const Polygon& receiver, const Polygon& source, double tolerance) {
  const double area_i = polygon_area(receiver), area_j = polygon_area(source);
  if (!(area_i > 0) || !(area_j > 0)) return 0.0;
  const Vec3 ni = polygon_normal(receiver), nj = polygon_normal(source);
  const Vec3 ci = polygon_centroid(receiver), cj = polygon_centroid(source);

  // Work in coordinates centred on the receiver and scaled to the pair: F is invariant, and ln r
  // stays O(1), so the edge terms (which cancel to A_i F_ij) keep their digits for distant pairs.
  const double scale = std::max({std::sqrt(area_i), std::sqrt(area_j), length(cj - ci)});
  const auto to_local = [&](const Polygon& p) {
    std::vector<Vec3> v(p.count);
    for (int k = 0; k < p.count; ++k) v[k] = (p.v[k] - ci) / scale;
    return v;
  };
  const std::vector<Vec3> vi = to_local(receiver), vj = to_local(source);
  const double eps = 1e-12;  // relative to the pair's scale, now 1

  // Only the part of each in front of the other's plane: this makes F one-sided and the contour
  // formula valid (see the top of this file).
  const std::vector<Vec3> front_i = clip(vi, vj[0], nj, eps);
  const std::vector<Vec3> front_j = clip(vj, vi[0], ni, eps);
  if (front_i.size() < 3 || front_j.size() < 3) return 0.0;
  // Coplanar: the clip kept everything on the plane, and cosθ = 0 there.
  double height_i = 0, height_j = 0;
  for (const Vec3& v : front_i) height_i = std::max(height_i, dot(v - vj[0], nj));
  for (const Vec3& v : front_j) height_j = std::max(height_j, dot(v - vi[0], ni));
  if (height_i <= eps || height_j <= eps) return 0.0;

  const std::vector<Edge> ei = edges_of(front_i, 1e-14), ej = edges_of(front_j, 1e-14);
  const double local_area_i = area_i / (scale * scale);
  // Absolute tolerance on the contour sum that keeps F within `tolerance`, shared by the pairs.
  const double pair_tol = tolerance * 2.0 * kPi * local_area_i / double(ei.size() * ej.size());
  double sum = 0.0;
  for (const Edge& a : ei)
    for (const Edge& b : ej) sum += edge_pair(a, b, pair_tol);
  // Each contour runs counter-clockwise about its own normal; with the normals facing each other
  // that orientation makes the double integral positive.
  const double f = sum / (2.0 * kPi * local_area_i);
  return std::max(f, 0.0);
}

}  // namespace walkrad
