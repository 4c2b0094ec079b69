#include "walkrad/pipeline/transmission.h"

#include <utility>

#include "walkrad/formats/error.h"
#include "walkrad/pipeline/hierarchy_mesher.h"

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

namespace {

Vec3 mean_received(const Hierarchy& h, uint32_t node, double& area) {
  const HNode& n = h[node];
  if (n.child_count == 0) {
    area = n.area;
    return (n.Hl + n.D) * n.area;
  }
  Vec3 sum;
  area = 0;
  for (uint32_t k = 0; k < n.child_count; ++k) {
    double a = 0;
    sum += mean_received(h, h.child(n, k), a);
    area += a;
  }
  return sum;
}

}  // namespace

Vec3 twin_received(const Hierarchy& h, const HNode& leaf, uint32_t twin_polygon) {
  const uint32_t node = leaf_at(h, h.polygon_root(twin_polygon), polygon_centroid(leaf.shape), leaf.depth);
  double area = 0;
  const Vec3 sum = mean_received(h, node, area);
  return area > 0 ? sum / area : Vec3{};
}

Effect plan_transmission(const Scene& scene, const std::string& method, const std::map<std::string, std::string>& overrides) {
  size_t count = 0;
  for (const Polygon& p : scene.polygons) count += scene.materials[p.material].transmits() ? 1 : 0;
  Effect e;
  e.on = count > 0 && method == "hierarchical";
  e.reason = count == 0 ? "no material transmits"
             : method != "hierarchical"
                 ? std::to_string(count) + " polygons transmit, but the classic method does not simulate transmission (use the hierarchical one)"
                 : std::to_string(count) + " polygons transmit (diffuse transmission): each gets a back-facing twin that passes light through";
  apply_override(e, "transmission", overrides);
  if (e.on && (count == 0 || method != "hierarchical"))
    throw InputError("--effect", "transmission", count == 0 ? "no material transmits" : "the classic method does not simulate transmission",
                     kExitBadArguments);
  return e;
}

}  // namespace walkrad
