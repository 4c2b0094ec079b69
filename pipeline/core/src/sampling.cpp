#include "walkrad/core/sampling.h"

#include <cmath>

namespace walkrad {

Vec3 sample_polygon(const Polygon& p, double u, double v) {
  if (p.count == 3) {
    const double su = std::sqrt(u);
    return p.v[0] * (1 - su) + p.v[1] * (su * (1 - v)) + p.v[2] * (su * v);
  }
  return p.v[0] * ((1 - u) * (1 - v)) + p.v[1] * (u * (1 - v)) + p.v[2] * (u * v) + p.v[3] * ((1 - u) * v);
}

}  // namespace walkrad
