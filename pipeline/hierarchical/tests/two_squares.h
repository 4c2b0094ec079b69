// A fixture of the solver's parts' tests (error_oracle_test, sweeps_test): two parallel unit squares a
// metre apart, ρ = 0.5, as a hierarchy of two element roots under one cluster, the lower one emitting
// `lower_emission` (the upper none). Radiosity and links are set by hand by each test.
#pragma once

#include <memory>

#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/testing/howell_catalogue.h"

namespace walkrad::test {

struct TwoSquares {
  Scene scene;
  ClusterTree tree;
  std::unique_ptr<Hierarchy> h;
  HierarchicalSettings settings;
  uint32_t lower = 0, upper = 0;

  explicit TwoSquares(double lower_emission = 0) {
    scene.materials.push_back({"grey", {0.5, 0.5, 0.5}, {0, 0, 0}});
    scene.materials.push_back({"lit", {0.5, 0.5, 0.5}, Vec3(1, 1, 1) * lower_emission});
    const RectanglePair pair = parallel_rectangles(1.0, 1.0, 1.0);
    scene.polygons = {pair.first, pair.second};
    scene.polygons[0].material = 1;
    tree = build_cluster_tree(scene);
    h = std::make_unique<Hierarchy>(scene, tree);
    lower = h->polygon_root(0);
    upper = h->polygon_root(1);
  }
};

}  // namespace walkrad::test
