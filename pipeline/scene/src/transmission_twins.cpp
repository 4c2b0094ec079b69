#include "walkrad/scene/transmission_twins.h"

#include <utility>

namespace walkrad {

std::vector<uint32_t> add_transmission_twins(Scene& scene) {
  const size_t n = scene.polygons.size();
  std::vector<uint32_t> twin(n, kNoTwin);
  for (size_t i = 0; i < n; ++i) {
    if (!scene.materials[scene.polygons[i].material].transmits()) continue;
    Polygon back = scene.polygons[i];
    std::swap(back.v[1], back.v[back.count - 1]);  // v0, v_last, ..., v1: the same corners, reversed
    twin[i] = uint32_t(scene.polygons.size());
    twin.push_back(uint32_t(i));
    scene.polygons.push_back(back);
  }
  return twin;
}

}  // namespace walkrad
