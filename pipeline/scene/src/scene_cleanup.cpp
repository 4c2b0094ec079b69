#include "walkrad/scene/scene_cleanup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <vector>

namespace walkrad {

uint64_t remove_duplicate_polygons(Scene& scene) {
  const Bounds b = scene.bounds();
  const double unit = std::max(1e-30, 1e-9 * length(b.diagonal()));
  using Key = std::vector<int64_t>;
  std::set<Key> seen;
  std::vector<Polygon> kept;
  kept.reserve(scene.polygons.size());
  uint64_t dropped = 0;
  for (const Polygon& p : scene.polygons) {
    std::vector<std::array<int64_t, 3>> corners;
    for (int k = 0; k < p.count; ++k)
      corners.push_back({std::llround((p.v[k].x - b.lo.x) / unit), std::llround((p.v[k].y - b.lo.y) / unit),
                         std::llround((p.v[k].z - b.lo.z) / unit)});
    std::sort(corners.begin(), corners.end());
    Key key;
    for (const auto& c : corners) key.insert(key.end(), c.begin(), c.end());
    const Vec3 n = polygon_normal(p);  // the same corners facing the other way are another surface
    key.push_back(n.x > 0.5 ? 1 : n.x < -0.5 ? -1 : 0);
    key.push_back(n.y > 0.5 ? 1 : n.y < -0.5 ? -1 : 0);
    key.push_back(n.z > 0.5 ? 1 : n.z < -0.5 ? -1 : 0);
    key.push_back(std::llround(n.x * 1e3) + 7 * std::llround(n.y * 1e3) + 49 * std::llround(n.z * 1e3));
    if (seen.insert(key).second) kept.push_back(p);
    else ++dropped;
  }
  scene.polygons.swap(kept);
  return dropped;
}

uint64_t separate_clear_glass(Scene& scene) {
  std::vector<Polygon> kept;
  kept.reserve(scene.polygons.size());
  uint64_t moved = 0;
  for (const Polygon& p : scene.polygons) {
    if (scene.materials[p.material].is_clear_glass()) {
      scene.glass.push_back(p);
      ++moved;
    } else {
      kept.push_back(p);
    }
  }
  if (moved) scene.polygons.swap(kept);
  return moved;
}

}  // namespace walkrad
