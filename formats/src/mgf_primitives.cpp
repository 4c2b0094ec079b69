// MGF's curved primitives as faces (mgf_geometry.h). The surfaces and their orientation are those of
// the MGF specification (entities sph, cyl, cone, ring, torus, prism); the tessellation is
// walkrad's: vertices on the true surface, `divisions` segments per quarter circle, as in MGF's
// own parser (mg_nqcdivs) and RenderPark.
#include <algorithm>
#include <cmath>

#include "mgf_geometry.h"

namespace walkrad::mgf {

namespace {


// u, v with (u, v, w) a right-handed orthonormal frame, w unit.
void axes(const Vec3& w, Vec3& u, Vec3& v) {
  const Vec3 helper = std::fabs(w.x) < 0.6 ? Vec3{1, 0, 0} : (std::fabs(w.y) < 0.6 ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
  u = normalize(cross(helper, w));
  v = cross(w, u);
}

void add(std::vector<Loop>& out, Loop l, bool inward) {
  if (inward) std::reverse(l.begin(), l.end());
  out.push_back(std::move(l));
}

}  // namespace

int quarter_divisions(double tolerance) {
  const double step = 2 * std::acos(1 - tolerance);  // the largest angle whose chord stays within tolerance
  return std::max(1, int(std::ceil((kPi / 2) / step - 1e-9)));
}

void tessellate_sphere(const Vec3& c, double radius, int divisions, std::vector<Loop>& out) {
  const double r = std::fabs(radius);
  const int rings = 2 * divisions, around = 4 * divisions;
  const double step = (kPi / 2) / divisions;
  auto at = [&](int i, int j) {
    const double theta = i * step, phi = (j % around) * step;
    return c + Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)) * r;
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < around; ++j) {
      if (i == 0) add(out, {at(0, 0), at(1, j), at(1, j + 1)}, radius < 0);
      else if (i == rings - 1) add(out, {at(i, j), at(rings, 0), at(i, j + 1)}, radius < 0);
      else add(out, {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}, radius < 0);
    }
}

void tessellate_cone(const Vec3& p1, double r1, const Vec3& p2, double r2, int divisions, std::vector<Loop>& out) {
  Vec3 u, v;
  axes(normalize(p2 - p1), u, v);
  const bool inward = r1 < 0 || r2 < 0;
  const double a = std::fabs(r1), b = std::fabs(r2);
  const int around = 4 * divisions;
  const double step = (kPi / 2) / divisions;
  auto dir = [&](int j) { return u * std::cos((j % around) * step) + v * std::sin((j % around) * step); };
  for (int j = 0; j < around; ++j) {
    // Counter-clockwise seen from outside: around the axis at p1, then along it to p2.
    if (a == 0) add(out, {p1, p2 + dir(j + 1) * b, p2 + dir(j) * b}, inward);
    else if (b == 0) add(out, {p1 + dir(j) * a, p1 + dir(j + 1) * a, p2}, inward);
    else add(out, {p1 + dir(j) * a, p1 + dir(j + 1) * a, p2 + dir(j + 1) * b, p2 + dir(j) * b}, inward);
  }
}

void tessellate_ring(const Vec3& c, const Vec3& n, double rmin, double rmax, int divisions, std::vector<Loop>& out) {
  Vec3 u, v;
  axes(normalize(n), u, v);
  const int around = 4 * divisions;
  const double step = (kPi / 2) / divisions;
  auto dir = [&](int j) { return u * std::cos((j % around) * step) + v * std::sin((j % around) * step); };
  for (int j = 0; j < around; ++j) {
    if (rmin == 0) add(out, {c, c + dir(j) * rmax, c + dir(j + 1) * rmax}, false);
    else add(out, {c + dir(j) * rmin, c + dir(j) * rmax, c + dir(j + 1) * rmax, c + dir(j + 1) * rmin}, false);
  }
}

void tessellate_torus(const Vec3& c, const Vec3& n, double rmin, double rmax, int divisions, std::vector<Loop>& out) {
  Vec3 u, w;
  const Vec3 axis = normalize(n);
  axes(axis, u, w);
  const bool inward = rmin < 0 || (rmin == 0 && rmax < 0);
  const double a = std::fabs(rmin), b = std::fabs(rmax);
  const double centre = (a + b) / 2, tube = (b - a) / 2;
  const int around = 4 * divisions;
  const double step = (kPi / 2) / divisions;
  auto at = [&](int i, int j) {  // i: around the tube, j: around the axis
    const double psi = (i % around) * step, phi = (j % around) * step;
    const Vec3 radial = u * std::cos(phi) + w * std::sin(phi);
    return c + radial * (centre + tube * std::cos(psi)) + axis * (tube * std::sin(psi));
  };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < around; ++j) add(out, {at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)}, inward);
}

void tessellate_prism(const Loop& base, double length, std::vector<Loop>& out) {
  Vec3 an;
  for (size_t i = 0; i < base.size(); ++i) an += cross(base[i], base[(i + 1) % base.size()]);
  const Vec3 offset = normalize(an) * -length;
  const size_t n = base.size();
  out.push_back(base);
  Loop top;
  for (size_t i = n; i-- > 0;) top.push_back(base[i] + offset);
  out.push_back(top);
  for (size_t i = 0; i < n; ++i) {
    const size_t prev = (i + n - 1) % n;
    out.push_back({base[i] + offset, base[i], base[prev], base[prev] + offset});
  }
}

}  // namespace walkrad::mgf
