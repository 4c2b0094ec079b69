#include "walkrad/hierarchical/directional_irradiance.h"

#include <cmath>

namespace walkrad {

namespace {

// The component index on the side of axis a that a vector with coordinate x faces.
size_t side(int a, double x) { return size_t(2 * a + (x > 0 ? 0 : 1)); }

}  // namespace

void DirectionalIrradiance::add(const HNode& cluster, const Vec3& u, double form_factor, const Vec3& B) {
  const double facing = projected_area(cluster, u);
  if (facing <= 0 || cluster.area <= 0) {
    // Nothing of the cluster faces the source (its F is then 0 or noise): spread it evenly.
    for (size_t k = 0; k < 6; ++k) {
      H[k] += B * form_factor;
      F[k] += form_factor;
    }
    return;
  }
  const double per_cosine = form_factor * cluster.area / facing;  // F over the cluster's mean cosine
  for (int a = 0; a < 3; ++a) {
    const double w = std::fabs(u[a]) * per_cosine;
    H[side(a, u[a])] += B * w;
    F[side(a, u[a])] += w;
  }
}

Vec3 DirectionalIrradiance::at(const Vec3& n) const {
  Vec3 out;
  for (int a = 0; a < 3; ++a) out += H[side(a, n[a])] * std::fabs(n[a]);
  return out;
}

double DirectionalIrradiance::row(const Vec3& n) const {
  double out = 0;
  for (int a = 0; a < 3; ++a) out += F[side(a, n[a])] * std::fabs(n[a]);
  return out;
}

DirectionalIrradiance& DirectionalIrradiance::operator+=(const DirectionalIrradiance& o) {
  for (size_t k = 0; k < 6; ++k) {
    H[k] += o.H[k];
    F[k] += o.F[k];
  }
  return *this;
}

Vec3 link_direction(const HNode& receiver, const HNode& source) {
  const Vec3 d = source.center - receiver.center;
  const double r = length(d);
  return r > 0 ? d / r : Vec3(0, 1, 0);
}

}  // namespace walkrad
