// Hard scenes for the stability suite, generated in code, and both solvers run on them the
// way `walkrad bake` runs them (contact splitting, Embree visibility, cluster-tree shaft culling), so
// that each test can hold the solution to an exact or bounded expectation.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include <tbb/global_control.h>

#include "walkrad/formats/scene.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/scene/contact_split.h"
#include "walkrad/plan/effect_plan.h"
#include "walkrad/classic/matrix_audit.h"
#include "walkrad/hierarchical/hierarchy_audit.h"
#include "walkrad/classic/form_factor_matrix.h"
#include "walkrad/classic/gauss_seidel.h"
#include "walkrad/classic/southwell.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/classic/subdivision.h"

namespace walkrad::stability {

inline Polygon quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, uint32_t material) {
  Polygon p;
  p.v = {a, b, c, d};
  p.count = 4;
  p.material = material;
  return p;
}

// The six faces of the box [lo, hi], facing inwards (inwards = true) or outwards.
inline void add_box(Scene& scene, Vec3 lo, Vec3 hi, uint32_t material, bool inwards) {
  const Vec3 x(hi.x - lo.x, 0, 0), y(0, hi.y - lo.y, 0), z(0, 0, hi.z - lo.z), o = lo;
  const Polygon faces[6] = {quad(o, o + x, o + x + z, o + z, material),         quad(o + y, o + y + z, o + y + x + z, o + y + x, material),
                            quad(o, o + y, o + y + x, o + x, material),         quad(o + z, o + z + x, o + z + x + y, o + z + y, material),
                            quad(o, o + z, o + z + y, o + y, material),         quad(o + x, o + x + y, o + x + y + z, o + x + z, material)};
  const Vec3 centre = (lo + hi) * 0.5;
  for (Polygon p : faces) {
    const bool faces_in = dot(polygon_normal(p), centre - polygon_centroid(p)) > 0;
    if (faces_in != inwards) std::swap(p.v[1], p.v[3]);
    scene.polygons.push_back(p);
  }
}

// A closed 2 m room of reflectance rho (material 0) with a square lamp of half-side h and emission e
// (material 1, ρ 0.5) centred on its ceiling, flush with it and facing down.
inline Scene room_with_lamp(const char* name, double rho, Vec3 e, double h) {
  Scene scene;
  scene.source = name;
  scene.materials.push_back({"wall", {rho, rho, rho}, {}});
  scene.materials.push_back({"lamp", {0.5, 0.5, 0.5}, e});
  add_box(scene, {0, 0, 0}, {2, 2, 2}, 0, true);
  Polygon lamp = quad({1 - h, 1 - h, 2}, {1 + h, 1 - h, 2}, {1 + h, 1 + h, 2}, {1 - h, 1 + h, 2}, 1);
  if (polygon_normal(lamp).z > 0) std::swap(lamp.v[1], lamp.v[3]);
  scene.polygons.push_back(lamp);
  return scene;
}

// Every vertex mapped to offset + scale · v (cameras are not used here).
inline Scene transformed(Scene scene, double scale, Vec3 offset) {
  for (Polygon& p : scene.polygons)
    for (uint8_t k = 0; k < p.count; ++k) p.v[k] = offset + p.v[k] * scale;
  return scene;
}

// A solution reduced to what the tests check: per element (classic) or leaf (hierarchical), in the
// solver's own order.
struct Solution {
  std::vector<Vec3> B, centroid;
  std::vector<double> area;
  std::vector<uint32_t> polygon;  // in the contact-split scene
  EnergyAudit audit;
  int iterations = 0;             // classic: Gauss-Seidel sweeps; hierarchical: sweeps over all rounds
  int corrections = 0;            // hierarchical: aggregation corrections over all rounds
  bool converged = false;
  Scene scene;                    // the contact-split scene the solution refers to
};

// southwell: progressive refinement (southwell.h) instead of Gauss-Seidel; iterations then counts shots.
inline Solution solve_classic(const Scene& input, double element_size, bool accelerate = true, int rays_per_point = 1,
                              bool southwell = false) {
  Solution s;
  ContactSplitStats split;
  s.scene = split_contacts(input, split);
  const RayScene rays(s.scene);
  const ClusterTree tree = build_cluster_tree(s.scene);
  const Subdivision sub = subdivide_uniform(s.scene, element_size);
  FormFactorCounts counts;
  FormFactorSettings ffs;
  ffs.rays_per_point = rays_per_point;
  const FormFactorMatrix f = compute_form_factors(sub, &rays, &tree, ffs, counts);
  std::vector<Vec3> rho, emission;
  for (const Element& e : sub.elements) {
    const Material& m = s.scene.materials[e.shape.material];
    rho.push_back(m.reflectance);
    emission.push_back(m.emission);
    s.area.push_back(e.area);
    s.centroid.push_back(e.centroid);
    s.polygon.push_back(e.polygon);
  }
  if (southwell) {
    SouthwellStats stats;
    s.B = solve_southwell(f, s.area, rho, emission, {}, stats);
    s.iterations = int(stats.shots);
    s.converged = stats.converged;
  } else {
    SolveSettings settings;
    settings.accelerate = accelerate;
    SolveStats stats;
    s.B = solve_gauss_seidel(f, s.area, rho, emission, settings, stats);
    s.iterations = stats.iterations;
    s.converged = stats.converged;
  }
  s.audit = audit_matrix(f, s.area, rho, emission, s.B);
  return s;
}

inline Solution solve_hierarchy(const Scene& input, double error = HierarchicalSettings{}.error, double tolerance = 1e-7,
                                bool accelerate = true) {
  Solution s;
  ContactSplitStats split;
  s.scene = split_contacts(input, split);
  const RayScene rays(s.scene);
  const ClusterTree tree = build_cluster_tree(s.scene);
  Hierarchy h(s.scene, tree);
  HierarchicalSettings settings;
  settings.error = error;
  settings.tolerance = tolerance;
  settings.accelerate = accelerate;
  // As a bake does (effect plan): a closed scene balances its transport, a convex one casts no ray.
  uint64_t closure_rays = 0, pressed_samples = 0;
  settings.closed = is_closed(s.scene, rays, closure_rays, pressed_samples);
  settings.visibility = !is_convex_enclosure(s.scene);
  HierarchicalStats stats;
  solve_hierarchical(h, rays, settings, stats);
  for (const IterationStats& it : stats.iterations) s.iterations += it.sweeps;
  s.corrections = int(stats.corrections);
  s.converged = stats.converged;
  for (const HNode& n : h.nodes())
    if (!n.cluster && n.child_count == 0) {
      s.B.push_back(n.B);
      s.centroid.push_back(polygon_centroid(n.shape));
      s.area.push_back(n.area);
      s.polygon.push_back(n.polygon);
    }
  s.audit = audit_hierarchy(h);
  return s;
}

// Runs solve() with at most `threads` worker threads.
template <class F>
Solution with_threads(int threads, F solve) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  return solve();
}

}  // namespace walkrad::stability
