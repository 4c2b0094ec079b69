// What bake() (bake.cpp) shares with the two methods' runs (run_classic.cpp, run_hierarchical.cpp):
// the phase clock and what a method hands back. Private to this stage.
#pragma once

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "checkpoint_file.h"
#include "walkrad/bake/bake.h"
#include "walkrad/bake/bake_caps.h"
#include "walkrad/output/surface_mesher.h"
#include "walkrad/plan/effect_plan.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/visibility/volume_visibility.h"

namespace walkrad::bake_detail {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

inline json vec_json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

// Phase times for report.json; the caps are checked as each phase starts (bake_caps.h).
class Phases {
 public:
  Phases(bool progress, const CapWatch& caps) : progress_(progress), caps_(caps) {}
  void check(const std::string& where) const { caps_.check(where); }
  void check_predicted(const std::string& where, uint64_t predicted_mb, const std::string& what) const {
    caps_.check_predicted(where, predicted_mb, what);
  }
  const CapWatch& caps() const { return caps_; }
  void start(const std::string& name) {
    caps_.check("before " + name);
    finish();
    name_ = name;
    t0_ = Clock::now();
    if (progress_) std::fprintf(stderr, "walkrad: %s\n", name.c_str());
  }
  void finish() {
    if (name_.empty()) return;
    // Memory at the phase's end: resident, and the process's peak so far (the phase where it jumps
    // is the one that set it: a large level's baseline against its links).
    phases_.push_back({{"name", name_},
                       {"seconds", std::chrono::duration<double>(Clock::now() - t0_).count()},
                       {"resident_mb", resident_memory_mb()},
                       {"peak_mb", peak_memory_mb()}});
    name_.clear();
  }
  const json& list() const { return phases_; }

 private:
  bool progress_;
  const CapWatch& caps_;
  std::string name_;
  Clock::time_point t0_;
  json phases_ = json::array();
};

// What a solver hands to the rest of the bake: a way to look up radiosity at a surface point (for
// exposure), a mesher (given the exposure; it adds its own counters to the first json, and may complete
// the solver's, the second: the estimate counts what the output mesh leaves), and its counters for
// report.json.
struct MethodResult {
  std::function<Vec3(uint32_t, const Vec3&)> radiosity_at;
  std::function<SurfaceMesh(double, json&, json&)> mesh;
  double surface_exposure = 1.0;  // exposure from the surfaces themselves, for bakes without viewpoints
  json counts, solver, energy, audit;
};

inline json energy_json(const Vec3& emitted, const Vec3& absorbed) {
  return {{"emitted_w", vec_json(emitted)}, {"absorbed_w", vec_json(absorbed)}};
}

// The classic method: uniform elements, the full form factor matrix, Gauss-Seidel (or one gather).
MethodResult run_classic(const BakeSettings& s, const Scene& scene, const RayScene& rays, const ClusterTree& tree,
                         const Bounds& bounds, const EffectPlan& plan, Phases& phases);

// The hierarchical method: importance from the viewpoints, then the refine-solve rounds.
MethodResult run_hierarchical(const BakeSettings& s, const Scene& scene, const RayScene& rays, const ClusterTree& tree,
                              const std::vector<Viewpoint>& views, const EffectPlan& plan, const std::vector<uint32_t>& twins,
                              const VolumeVisibility* volumes, const CheckpointFile& checkpoint, Phases& phases);

}  // namespace walkrad::bake_detail
