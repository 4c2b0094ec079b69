// The transmittance of a thin pane of clear glass (a flat slab of index n in air, not absorbing), seen
// at angle θ from its normal: at each face the Fresnel reflectance (Born & Wolf §1.5)
//   r_s = (cos θ − n cos θt) / (cos θ + n cos θt),  r_p = (n cos θ − cos θt) / (n cos θ + cos θt),
//   sin θt = sin θ / n,  R = r²,
// and between the two faces every inner reflection summed incoherently, T = (1 − R) / (1 + R) per
// polarisation, unpolarised light the mean of the two. n = 1.5 at normal incidence: R = 0.04, T = 0.923.
#pragma once

#include <algorithm>
#include <cmath>

namespace walkrad {

inline double pane_transmittance(double cos_theta, double ior) {
  const double c = std::clamp(std::fabs(cos_theta), 0.0, 1.0);
  if (c <= 0) return 0.0;
  const double s2 = (1 - c * c) / (ior * ior);
  const double ct = std::sqrt(std::max(0.0, 1 - s2));
  const double rs = (c - ior * ct) / (c + ior * ct), rp = (ior * c - ct) / (ior * c + ct);
  const double Rs = rs * rs, Rp = rp * rp;
  return 0.5 * ((1 - Rs) / (1 + Rs) + (1 - Rp) / (1 + Rp));
}

}  // namespace walkrad
