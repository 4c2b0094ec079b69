#include "walkrad/hierarchical/cluster_radiosity.h"

#include <algorithm>

namespace walkrad {

std::vector<std::array<Vec3, 6>> facing_radiosity(const Hierarchy& h, const std::vector<Vec3>& value) {
  const std::vector<HNode>& nodes = h.nodes();
  std::vector<std::array<Vec3, 6>> out(nodes.size());
  // Children come after their parents: from the end, each node is complete before its parent takes it.
  for (size_t k = nodes.size(); k-- > 0;) {
    const HNode& n = nodes[k];
    if (n.parent < 0) continue;
    std::array<Vec3, 6>& parent = out[size_t(n.parent)];
    if (n.cluster) {
      for (size_t a = 0; a < 6; ++a) parent[a] += out[k][a];
    } else if (nodes[size_t(n.parent)].cluster) {  // an element root: its leaves share its normal
      for (size_t a = 0; a < 6; ++a) parent[a] += value[k] * double(n.facing[a]);
    }
  }
  return out;
}

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
