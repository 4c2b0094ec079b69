#include "walkrad/pipeline/bake.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "walkrad/formats/chunk_writer.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/manifest.h"
#include "walkrad/formats/walkthrough.h"
#include "walkrad/pipeline/cluster_tree.h"
#include "walkrad/pipeline/contact_split.h"
#include "walkrad/pipeline/exposure.h"
#include "walkrad/pipeline/form_factor_matrix.h"
#include "walkrad/pipeline/gauss_seidel.h"
#include "walkrad/pipeline/progress.h"
#include "walkrad/pipeline/staged_output.h"
#include "walkrad/pipeline/subdivision.h"
#include "walkrad/pipeline/vertex_mesher.h"

#ifndef WALKRAD_VERSION
#define WALKRAD_VERSION "0.0.0"
#endif

namespace walkrad {

namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

// FNV-1a 64 of a file's bytes: identifies the input in the manifest (not a security hash).
std::string hash_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  uint64_t h = 0xcbf29ce484222325ull;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) h = (h ^ uint8_t(buf[i])) * 0x100000001b3ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

json vec_json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

void write_json(const std::string& path, const json& j) {
  std::ofstream out(path, std::ios::binary);
  out << j.dump(2) << '\n';
  if (!out) throw OutputError(path + ": cannot write");
}

// Phase times for report.json.
class Phases {
 public:
  explicit Phases(bool progress) : progress_(progress) {}
  void start(const std::string& name) {
    finish();
    name_ = name;
    t0_ = Clock::now();
    if (progress_) std::fprintf(stderr, "walkrad: %s\n", name.c_str());
  }
  void finish() {
    if (name_.empty()) return;
    phases_.push_back({{"name", name_}, {"seconds", std::chrono::duration<double>(Clock::now() - t0_).count()}});
    name_.clear();
  }
  const json& list() const { return phases_; }

 private:
  bool progress_;
  std::string name_;
  Clock::time_point t0_;
  json phases_ = json::array();
};

// Element of `polygon` whose centroid is nearest to p (elements of a polygon are contiguous).
size_t element_at(const Subdivision& sub, uint32_t polygon, const Vec3& p) {
  size_t best = sub.first_element[polygon];
  double best_d = INFINITY;
  for (size_t e = sub.first_element[polygon]; e < sub.first_element[polygon + 1]; ++e) {
    const double d = dot(sub.elements[e].centroid - p, sub.elements[e].centroid - p);
    if (d < best_d) { best_d = d; best = e; }
  }
  return best;
}

}  // namespace

json BakeSettings::to_json() const {
  return {{"method", method}, {"element_size", element_size}, {"rays_per_point", rays_per_point},
          {"exposure", exposure}, {"tolerance", tolerance}, {"max_iterations", max_iterations}};
}

BakeSummary bake(const BakeSettings& s) {
  const auto t_start = Clock::now();
  if (s.method != "classic") throw InputError("--method", "", "unknown method '" + s.method + "' (available: classic)", kExitBadArguments);
  std::unique_ptr<tbb::global_control> limit;
  if (s.threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(s.threads));
  const int threads = s.threads > 0 ? s.threads : tbb::info::default_concurrency();

  Phases phases(s.progress);
  phases.start("read");
  const Scene input = read_scene(s.scene);
  std::vector<Viewpoint> views = s.views.empty() ? input.cameras : read_walkthrough(s.views);
  for (const std::string& w : input.warnings) std::fprintf(stderr, "walkrad: warning: %s: %s\n", s.scene.c_str(), w.c_str());
  bool any_emitter = false;
  for (const Polygon& p : input.polygons) any_emitter = any_emitter || input.materials[p.material].emits();
  if (!any_emitter) throw InputError(s.scene, "", "the scene has no emitter (no material with emission): nothing to bake");
  // Fail on an unwritable destination before the long work, not after it.
  StagedOutput out(s.output);

  phases.start("subdivide");
  const Bounds bounds = input.bounds();
  ContactSplitStats split_stats;
  const Scene scene = split_contacts(input, split_stats);
  const double element_size = s.element_size > 0 ? s.element_size : length(bounds.diagonal()) / 30.0;
  const Subdivision sub = subdivide_uniform(scene, element_size);
  const size_t n = sub.elements.size();

  phases.start("form factors");
  const RayScene rays(scene);
  const ClusterTree tree = build_cluster_tree(scene);
  FormFactorSettings ffs;
  ffs.rays_per_point = std::max(1, s.rays_per_point);
  FormFactorCounts counts;
  FormFactorMatrix f;
  {
    Progress progress("form factors", n, s.progress);
    f = compute_form_factors(sub, &rays, &tree, ffs, counts, [&](size_t done) { progress.update(done); });
  }

  phases.start("solve");
  std::vector<Vec3> rho(n), emission(n);
  std::vector<double> area(n);
  for (size_t i = 0; i < n; ++i) {
    const Material& m = scene.materials[sub.elements[i].shape.material];
    rho[i] = m.reflectance;
    emission[i] = m.emission;
    area[i] = sub.elements[i].area;
  }
  SolveSettings solve;
  solve.tolerance = s.tolerance;
  solve.max_iterations = s.max_iterations;
  SolveStats stats;
  const std::vector<Vec3> b = solve_gauss_seidel(f, rho, emission, solve, stats);
  const EnergyBalance energy = energy_balance(f, area, rho, emission, b);
  for (const Vec3& v : b)
    if (!is_finite(v)) throw std::runtime_error("the solution is not finite (please report this scene)");

  phases.start("exposure");
  uint64_t exposure_rays = 0;
  double exposure = s.exposure;
  if (exposure <= 0) {
    exposure = auto_exposure(
        views, rays, 64, [&](uint32_t poly, const Vec3& p) { return b[element_at(sub, poly, p)]; },
        [&](uint32_t poly) { return scene.materials[scene.polygons[poly].material].emits(); }, exposure_rays);
    if (views.empty()) {
      // No viewpoint: expose for the 95th percentile of the surfaces themselves.
      std::vector<double> lum;
      for (size_t i = 0; i < n; ++i)
        if (!scene.materials[sub.elements[i].shape.material].emits()) lum.push_back(luminance(b[i]) / kPi);
      if (!lum.empty()) {
        const size_t p95 = std::min(lum.size() - 1, size_t(0.95 * double(lum.size())));
        std::nth_element(lum.begin(), lum.begin() + p95, lum.end());
        if (lum[p95] > 0) exposure = 0.9 / lum[p95];
      }
    }
  }

  phases.start("mesh");
  const ChunkMesh mesh = mesh_elements(sub, b, exposure);

  phases.start("write");
  Manifest manifest;
  manifest.tool = std::string("walkrad ") + WALKRAD_VERSION;
  manifest.scene_file = s.scene;
  manifest.scene_hash = hash_file(s.scene);
  manifest.bounds = mesh.bounds();
  manifest.exposure = exposure;
  manifest.viewpoints = views;
  manifest.settings = s.to_json();
  manifest.settings["element_size"] = element_size;
  ChunkInfo chunk;
  chunk.file = "chunk-0000.glb";
  chunk.bounds = manifest.bounds;
  chunk.triangles = mesh.triangle_count();
  chunk.bytes = write_chunk(out.path(chunk.file), mesh);
  manifest.chunks.push_back(chunk);
  write_json(out.path("manifest.json"), manifest_to_json(manifest));
  phases.finish();

  const double seconds = std::chrono::duration<double>(Clock::now() - t_start).count();
  json report = {
      {"format", "walkrad-report"},
      {"version", 1},
      {"method", s.method},
      {"threads", threads},
      {"phases", phases.list()},
      {"total_seconds", seconds},
      {"counts",
       {{"input_polygons", input.polygons.size()}, {"polygons", scene.polygons.size()},
        {"contact_cuts", split_stats.cuts}, {"elements", n}, {"form_factor_pairs", counts.pairs},
        {"unoccluded_pairs", counts.unoccluded}, {"form_factor_entries", counts.nonzero},
        {"visibility_rays", counts.rays}, {"exposure_rays", exposure_rays},
        {"iterations", stats.iterations}, {"triangles", mesh.triangle_count()}, {"viewpoints", views.size()},
        {"dropped_degenerate", input.dropped_degenerate}}},
      {"solver", {{"converged", stats.converged}, {"last_update", stats.last_update}, {"tolerance", s.tolerance}}},
      {"energy", {{"emitted_w", vec_json(energy.emitted)}, {"absorbed_w", vec_json(energy.absorbed)},
                  {"residual_w", vec_json(energy.residual)}}},
      {"warnings", input.warnings},
  };
  write_json(out.path("report.json"), report);
  out.commit();

  BakeSummary summary;
  summary.output = s.output;
  summary.elements = n;
  summary.triangles = mesh.triangle_count();
  summary.viewpoints = views.size();
  summary.exposure = exposure;
  summary.seconds = seconds;
  return summary;
}

}  // namespace walkrad
