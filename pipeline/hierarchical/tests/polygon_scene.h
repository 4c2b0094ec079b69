// A fixture of the solver's parts' tests (link_evaluator_test, refinement_test): a scene of the given
// polygons, one grey material (ρ = 0.5), with what the parts read: its cluster tree, its rays and its
// hierarchy, at default settings.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad::test {

struct PolygonScene {
  Scene scene;
  ClusterTree tree;
  std::unique_ptr<RayScene> rays;
  std::unique_ptr<Hierarchy> h;
  HierarchicalSettings settings;

  explicit PolygonScene(std::vector<Polygon> polygons) {
    scene.materials.push_back({"grey", {0.5, 0.5, 0.5}, {0, 0, 0}});
    scene.polygons = std::move(polygons);
    tree = build_cluster_tree(scene);
    rays = std::make_unique<RayScene>(scene);
    h = std::make_unique<Hierarchy>(scene, tree);
  }
  uint32_t root(uint32_t polygon) const { return h->polygon_root(polygon); }
};

}  // namespace walkrad::test
