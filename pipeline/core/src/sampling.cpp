#include "walkrad/core/sampling.h"

#include <algorithm>
#include <cmath>

namespace walkrad {

Vec3 sample_polygon(const Polygon& p, double u, double v) {
  if (p.count == 3) {
    const double su = std::sqrt(u);
    return p.v[0] * (1 - su) + p.v[1] * (su * (1 - v)) + p.v[2] * (su * v);
  }
  return p.v[0] * ((1 - u) * (1 - v)) + p.v[1] * (u * (1 - v)) + p.v[2] * (u * v) + p.v[3] * ((1 - u) * v);
}

void frame(const Vec3& n, Vec3& t, Vec3& b) {
  t = normalize(cross(std::fabs(n.x) > 0.5 ? Vec3(0, 1, 0) : Vec3(1, 0, 0), n));
  b = cross(n, t);
}

Vec3 cosine_direction(const Vec3& n, Rng& rng) {
  Vec3 t, b;
  frame(n, t, b);
  const double r = std::sqrt(rng.uniform()), phi = 2 * kPi * rng.uniform();
  return t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - r * r));
}

Vec3 cone_direction(const Vec3& axis, double cone, Rng& rng) {
  const double u = rng.uniform();
  return cap_direction(axis, cone, u, rng.uniform());
}

Vec3 cap_direction(const Vec3& axis, double cone, double u, double v) {
  Vec3 t, b;
  frame(axis, t, b);
  const double z = 1 - u * (1 - std::cos(cone)), phi = 2 * kPi * v;
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + axis * z;
}

}  // namespace walkrad
