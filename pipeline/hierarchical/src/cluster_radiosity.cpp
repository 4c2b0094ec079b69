#include "walkrad/hierarchical/cluster_radiosity.h"

#include <algorithm>

namespace walkrad {

Vec3 radiosity_towards(const HNode& n, const std::array<Vec3, 6>& facing_radiosity, const Vec3& u, const Vec3& mean) {
  if (!n.cluster) return mean;
  Vec3 sum;
  double area = 0;
  for (int a = 0; a < 3; ++a) {
    const double plus = std::max(0.0, u[a]), minus = std::max(0.0, -u[a]);
    sum += facing_radiosity[size_t(2 * a)] * plus + facing_radiosity[size_t(2 * a + 1)] * minus;
    area += double(n.facing[size_t(2 * a)]) * plus + double(n.facing[size_t(2 * a + 1)]) * minus;
  }
  return area > 0 ? sum / area : mean;
}

}  // namespace walkrad
