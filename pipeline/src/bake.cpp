#include "walkrad/pipeline/bake.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/info.h>

#include "walkrad/formats/chunk_writer.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/manifest.h"
#include "walkrad/formats/walkthrough.h"
#include "walkrad/pipeline/chunk_optimizer.h"
#include "walkrad/pipeline/chunking.h"
#include "walkrad/pipeline/cluster_tree.h"
#include "walkrad/pipeline/effect_plan.h"
#include "walkrad/pipeline/contact_split.h"
#include "walkrad/pipeline/energy_audit.h"
#include "walkrad/pipeline/extinction_grid.h"
#include "walkrad/pipeline/exposure.h"
#include "walkrad/pipeline/form_factor_matrix.h"
#include "walkrad/pipeline/gauss_seidel.h"
#include "walkrad/pipeline/hierarchical_solver.h"
#include "walkrad/pipeline/hierarchy_mesher.h"
#include "walkrad/pipeline/punctual_lights.h"
#include "walkrad/pipeline/view_importance.h"
#include "walkrad/pipeline/progress.h"
#include "walkrad/pipeline/scene_cleanup.h"
#include "walkrad/pipeline/staged_output.h"
#include "walkrad/pipeline/subdivision.h"
#include "walkrad/pipeline/texture_sampling.h"
#include "walkrad/pipeline/transmission.h"
#include "walkrad/pipeline/vertex_mesher.h"
#include "walkrad/pipeline/volume_visibility.h"

#ifndef WALKRAD_VERSION
#define WALKRAD_VERSION "0.0.0"
#endif

namespace walkrad {

namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

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

// Identifies what the extinction grid is made from: every polygon's corners and the volume settings
// (FNV-1a 64 over their bytes). A rebake with the same key reuses the grid.
std::string volume_key(const Scene& scene, const VolumeSettings& vs) {
  uint64_t h = 0xcbf29ce484222325ull;
  auto add = [&](const void* data, size_t size) {
    const auto* bytes = static_cast<const uint8_t*>(data);
    for (size_t k = 0; k < size; ++k) h = (h ^ bytes[k]) * 0x100000001b3ull;
  };
  for (const Polygon& p : scene.polygons) {
    add(&p.count, sizeof p.count);
    for (int k = 0; k < p.count; ++k) add(&p.v[size_t(k)], sizeof(Vec3));
  }
  add(&vs.min_polygons, sizeof vs.min_polygons);
  add(&vs.feature_ratio, sizeof vs.feature_ratio);
  add(&vs.small_object, sizeof vs.small_object);
  add(&vs.max_dispersion, sizeof vs.max_dispersion);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

void write_json(const std::string& path, const json& j) {
  std::ofstream out(path, std::ios::binary);
  out << j.dump(2) << '\n';
  if (!out) throw OutputError(path + ": cannot write");
}

// Phase times for report.json; the caps are checked as each phase starts (bake_caps.h).
class Phases {
 public:
  Phases(bool progress, const CapWatch& caps) : progress_(progress), caps_(caps) {}
  void check(const std::string& where) const { caps_.check(where); }
  void start(const std::string& name) {
    caps_.check("before " + name);
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
  const CapWatch& caps_;
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


// What a solver hands to the rest of the bake: a way to look up radiosity at a surface point (for
// exposure), a mesher, and its counters for report.json.
struct MethodResult {
  std::function<Vec3(uint32_t, const Vec3&)> radiosity_at;
  std::function<SurfaceMesh(double)> mesh;
  double surface_exposure = 1.0;  // exposure from the surfaces themselves, for bakes without viewpoints
  json counts, solver, energy, audit;
};

json energy_json(const Vec3& emitted, const Vec3& absorbed) {
  return {{"emitted_w", vec_json(emitted)}, {"absorbed_w", vec_json(absorbed)}};
}

MethodResult solve_classic(const BakeSettings& s, const Scene& scene, const RayScene& rays, const ClusterTree& tree,
                           const Bounds& bounds, const EffectPlan& plan, Phases& phases) {
  phases.start("subdivide");
  const double element_size = s.element_size > 0 ? s.element_size : length(bounds.diagonal()) / 30.0;
  auto sub = std::make_shared<Subdivision>(subdivide_uniform(scene, element_size));
  const size_t n = sub->elements.size();

  phases.start("form factors");
  FormFactorSettings ffs;
  ffs.rays_per_point = std::max(1, s.rays_per_point);
  ffs.visibility = plan.visibility.on;
  FormFactorCounts counts;
  FormFactorMatrix f;
  {
    Progress progress("form factors", n, s.progress);
    f = compute_form_factors(*sub, &rays, &tree, ffs, counts, [&](size_t done) {
      phases.check("form factors");
      progress.update(done);
    });
  }

  phases.start("solve");
  std::vector<Vec3> rho(n), emission(n), direct(n);
  std::vector<double> area(n);
  uint64_t light_rays = 0;
  if (plan.punctual.on) {  // punctual lights: each element's irradiance, 4 × 4 points (punctual_lights.h)
    std::vector<uint64_t> cast(n, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i)
        direct[i] = direct_irradiance(sub->elements[i].shape, scene.lights, plan.visibility.on ? &rays : nullptr, 4, cast[i]).mean;
    });
    for (uint64_t c : cast) light_rays += c;
  }
  for (size_t i = 0; i < n; ++i) {
    const Material& m = scene.materials[sub->elements[i].shape.material];
    SurfaceColour c{m.reflectance, m.emission};
    if (plan.textures.on) c = element_colour(scene, sub->elements[i].shape);
    rho[i] = c.reflectance;
    // What punctual lights give an element, it reflects like emitted light: E + ρ D.
    emission[i] = c.emission + mul(c.reflectance, direct[i]);
    area[i] = sub->elements[i].area;
  }
  SolveSettings solve;
  solve.tolerance = s.tolerance;
  solve.max_iterations = s.max_iterations;
  SolveStats stats;
  auto b = std::make_shared<std::vector<Vec3>>();
  if (plan.indirect.on) {
    *b = solve_gauss_seidel(f, area, rho, emission, solve, stats);
  } else {  // direct light only: B = E + ρ (F E + D), one gather of the surfaces' own emission
    b->resize(n);
    for (size_t i = 0; i < n; ++i) {
      Vec3 h;
      for (uint64_t k = f.row_start[i]; k < f.row_start[i + 1]; ++k)
        h += scene.materials[sub->elements[f.column[k]].shape.material].emission * f.value[k];
      (*b)[i] = emission[i] + mul(rho[i], h);
    }
    stats.iterations = 1;
    stats.converged = true;
  }
  const EnergyBalance energy = energy_balance(f, area, rho, emission, *b);
  for (const Vec3& v : *b)
    if (!is_finite(v)) throw std::runtime_error("the solution is not finite (please report this scene)");

  MethodResult r;
  r.radiosity_at = [sub, b](uint32_t poly, const Vec3& p) { return (*b)[element_at(*sub, poly, p)]; };
  r.mesh = [sub, b](double exposure) { return mesh_elements(*sub, *b, exposure); };
  std::vector<double> lum;
  for (size_t i = 0; i < n; ++i)
    if (!scene.materials[sub->elements[i].shape.material].emits()) lum.push_back(luminance((*b)[i]) / kPi);
  r.surface_exposure = exposure_for(std::move(lum));
  r.counts = {{"elements", n}, {"form_factor_pairs", counts.pairs}, {"unoccluded_pairs", counts.unoccluded},
              {"form_factor_entries", counts.nonzero}, {"visibility_rays", counts.rays}, {"iterations", stats.iterations},
              {"corrections", stats.corrections}, {"light_rays", light_rays}};
  r.solver = {{"element_size", element_size}, {"converged", stats.converged}, {"last_update", stats.last_update},
              {"tolerance", s.tolerance}};
  r.energy = energy_json(energy.emitted, energy.absorbed);
  r.energy["residual_w"] = vec_json(energy.residual);
  r.audit = audit_json(audit_matrix(f, area, rho, emission, *b));
  return r;
}

// Where the bake is still coarse, per stretch of the walkthrough: the walkthrough's frames are cut
// into at most 8 consecutive segments; each segment's direct importance (its primary-ray hits, scaled
// like the solver's so that Σ R = Σ A) weighs every final link: the largest and the summed
// B_j · R_i · ρ_i · F_ij, in W. Direct importance only: light reaching the view after more bounces
// is not attributed.
json error_per_segment(const Hierarchy& h, const std::vector<ViewHit>& hits, size_t view_count) {
  json out = json::array();
  if (hits.empty() || view_count == 0) return out;
  constexpr size_t kSegments = 8;
  const size_t segments = std::min(kSegments, view_count);
  double total = 0;
  for (const ViewHit& hit : hits) total += hit.weight;
  const double scale = total > 0 ? h[h.root()].area / total : 0.0;
  std::vector<std::array<double, kSegments>> r(h.nodes().size(), std::array<double, kSegments>{});
  for (const ViewHit& hit : hits) {
    const uint32_t leaf = leaf_at(h, h.polygon_root(hit.polygon), hit.point);
    r[leaf][std::min(segments - 1, size_t(hit.view) * segments / view_count)] += hit.weight * scale;
  }
  for (size_t i = h.nodes().size(); i-- > 1;)  // children come after their parents
    for (size_t k = 0; k < segments; ++k) r[size_t(h[uint32_t(i)].parent)][k] += r[i][k];
  std::vector<double> largest(segments, 0.0), sum(segments, 0.0);
  for (uint32_t i = 0; i < h.nodes().size(); ++i)
    for (const Link& l : h[i].links)
      for (size_t k = 0; k < segments; ++k) {
        const double e = luminance(h[l.source].B) * r[i][k] * luminance(h[i].rho) * l.F;
        largest[k] = std::max(largest[k], e);
        sum[k] += e;
      }
  for (size_t k = 0; k < segments; ++k)
    out.push_back({{"first_view", k * view_count / segments}, {"last_view", (k + 1) * view_count / segments - 1},
                   {"largest_w", largest[k]}, {"sum_w", sum[k]}});
  return out;
}

MethodResult solve_hierarchical(const BakeSettings& s, const Scene& scene, const RayScene& rays, const ClusterTree& tree,
                                const std::vector<Viewpoint>& views, const EffectPlan& plan, const std::vector<uint32_t>& twins,
                                const VolumeVisibility* volumes, Phases& phases) {
  auto h = std::make_shared<Hierarchy>(scene, tree, plan.textures.on);
  uint64_t view_rays = 0;
  std::vector<ViewHit> hits;
  if (!views.empty()) {
    phases.start("importance");
    hits = cast_view_rays(views, rays, 128, 64, view_rays);
    if (plan.importance.on) h->set_view_hits(hits);
  }
  phases.start("solve");
  HierarchicalSettings hs;
  hs.epsilon = s.epsilon;
  hs.min_area = s.min_area;
  hs.rays = std::max(1, s.rays_per_point) * 16;
  hs.tolerance = std::max(s.tolerance, 1e-6);
  hs.gauss_seidel = s.solver == "gauss-seidel";
  hs.visibility = plan.visibility.on;
  hs.indirect = plan.indirect.on;
  hs.closed = plan.closure.on;
  if (plan.punctual.on) hs.lights = &scene.lights;
  if (plan.transmission.on) hs.twins = &twins;
  hs.volumes = volumes;
  HierarchicalStats stats;
  const auto t0 = Clock::now();
  auto round_start = t0;
  uint64_t previous_new = 0;
  solve_hierarchical(*h, rays, hs, stats, [&](const IterationStats& it) {
    phases.check("solve round " + std::to_string(stats.iterations.size()));
    const auto now = Clock::now();
    const double left = refinement_seconds_left(previous_new, it.new_links, std::chrono::duration<double>(now - round_start).count());
    previous_new = it.new_links;
    round_start = now;
    if (!s.progress) return;
    char eta[48] = "remaining unknown";
    if (left >= 0) std::snprintf(eta, sizeof eta, "about %.0f s left", left);
    std::fprintf(stderr, "walkrad: solve round %zu: %llu links (+%llu), %llu elements, change %.2e, %.1f s, %s\n",
                 stats.iterations.size(), static_cast<unsigned long long>(it.links),
                 static_cast<unsigned long long>(it.new_links), static_cast<unsigned long long>(it.elements), it.change,
                 std::chrono::duration<double>(now - t0).count(), eta);
  });
  for (const HNode& n : h->nodes())
    if (!is_finite(n.B)) throw std::runtime_error("the solution is not finite (please report this scene)");

  MethodResult r;
  r.radiosity_at = [h](uint32_t poly, const Vec3& p) {
    // The element root of an input polygon: a leaf cluster's children, found through the tree.
    return (*h)[leaf_at(*h, h->polygon_root(poly), p)].B;
  };
  r.mesh = [h](double exposure) { return mesh_hierarchy(*h, exposure); };
  std::vector<double> lum;
  for (const HNode& n : h->nodes())
    if (!n.cluster && !n.child_count && !n.emission.x && !n.emission.y && !n.emission.z) lum.push_back(luminance(n.B) / kPi);
  r.surface_exposure = exposure_for(std::move(lum));
  json rounds = json::array();
  for (const IterationStats& it : stats.iterations)
    rounds.push_back({{"links", it.links}, {"new_links", it.new_links}, {"sweeps", it.sweeps}, {"elements", it.elements}, {"rays", it.rays},
                      {"change", it.change}, {"emitted_w", vec_json(it.emitted)}, {"absorbed_w", vec_json(it.absorbed)},
                      {"residual_w", vec_json(it.residual)}, {"clamped_leaves", it.clamped_leaves}});
  r.counts = {{"elements", h->element_count()}, {"links", stats.links}, {"refinements", stats.refinements},
              {"unoccluded_links", stats.unoccluded_links}, {"exact_links", stats.exact_links},
              {"volume_links", stats.volume_links}, {"grid_segments", stats.grid_segments},
              {"monte_carlo_links", stats.monte_carlo_links},
              {"visibility_rays", stats.rays}, {"importance_rays", view_rays}, {"iterations", stats.iterations.size()},
              {"light_rays", stats.light_rays}, {"light_refinements", stats.light_refinements}};
  r.solver = {{"error_per_segment", error_per_segment(*h, hits, views.size())},
              {"iteration", s.solver},
              {"oracle", stats.oracle}, {"epsilon", s.epsilon}, {"epsilon_w", stats.epsilon_absolute},
              {"converged", stats.converged}, {"tolerance", hs.tolerance}, {"rounds", rounds},
              {"left_error_max_w", stats.left_error_max}, {"left_error_sum_w", stats.left_error_sum},
              {"corrections", stats.corrections},
              {"balance", {{"iterations", stats.balance_iterations}, {"row_error", stats.balance_row_error},
                           {"column_error", stats.balance_column_error}, {"unbalanced_leaves", stats.balance_unbalanced}}}};
  const IterationStats& last = stats.iterations.back();
  r.energy = energy_json(last.emitted, last.absorbed);
  r.energy["residual_w"] = vec_json(last.residual);
  r.audit = audit_json(audit_hierarchy(*h, plan.transmission.on ? &twins : nullptr));
  return r;
}
}  // namespace

json BakeSettings::to_json() const {
  return {{"method", method},     {"solver", solver},       {"epsilon", epsilon},     {"view_independent", view_independent},     {"min_area", min_area},
          {"element_size", element_size}, {"rays", rays_per_point}, {"exposure", exposure},
          {"tolerance", tolerance}, {"max_iterations", max_iterations}, {"chunk_triangles", chunk_triangles},
          {"compress", compress}, {"position_tolerance", position_tolerance}, {"radiosity_tolerance", radiosity_tolerance},
          {"effects", effects}, {"volume_min_polygons", volume_min_polygons}, {"volume_penumbra_ratio", volume_penumbra_ratio}};
}

BakeSummary bake(const BakeSettings& s) {
  const auto t_start = Clock::now();
  if (s.method != "classic" && s.method != "hierarchical")
    throw InputError("--method", "", "unknown method '" + s.method + "' (available: hierarchical, classic)", kExitBadArguments);
  std::unique_ptr<tbb::global_control> limit;
  if (s.threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(s.threads));
  const int threads = s.threads > 0 ? s.threads : tbb::info::default_concurrency();

  const CapWatch caps(s.caps, s.scene);
  Phases phases(s.progress, caps);
  phases.start("read");
  Scene input = read_scene(s.scene);
  if (const uint64_t copies = remove_duplicate_polygons(input))
    input.warnings.push_back(std::to_string(copies) + " duplicate polygons (same corners, same facing) dropped");
  std::vector<Viewpoint> views = s.views.empty() ? input.cameras : read_walkthrough(s.views);
  for (const std::string& w : input.warnings) std::fprintf(stderr, "walkrad: warning: %s: %s\n", s.scene.c_str(), w.c_str());
  bool any_emitter = false;
  for (const Polygon& p : input.polygons) any_emitter = any_emitter || input.materials[p.material].emits();
  for (const PunctualLight& l : input.lights) any_emitter = any_emitter || max_component(l.intensity) > 0;
  if (!any_emitter)
    throw InputError(s.scene, "", "the scene has no emitter (no material with emission, no punctual light): nothing to bake");
  // Fail on an unwritable destination before the long work, not after it.
  StagedOutput out(s.output);

  phases.start("prepare");
  const Bounds bounds = input.bounds();
  ContactSplitStats split_stats;
  Scene scene = split_contacts(input, split_stats);
  // Transmission is decided first: its twins (back faces) are geometry, in the rays and the tree.
  const Effect transmission = plan_transmission(scene, s.method, s.effects);
  const std::vector<uint32_t> twins = transmission.on ? add_transmission_twins(scene) : std::vector<uint32_t>{};
  const RayScene rays(scene);
  const ClusterTree tree = build_cluster_tree(scene);
  VolumeSettings volume_settings;
  volume_settings.min_polygons = s.volume_min_polygons;
  volume_settings.penumbra_ratio = s.volume_penumbra_ratio;
  const VolumeClusters volume_clusters = s.method == "hierarchical" ? find_volume_clusters(scene, tree, volume_settings) : VolumeClusters{};
  EffectPlan plan = plan_effects(scene, rays, views, s.view_independent, s.method, s.effects, &volume_clusters);
  plan.transmission = transmission;
  if (s.explain) std::printf("walkrad: effect plan for %s:\n%s", s.scene.c_str(), plan.explain().c_str());
  // The extinction grid: reused from the previous bake in this folder when it was made from the same
  // geometry and settings (its key), else rasterised.
  ExtinctionGrid grid;
  std::unique_ptr<RayScene> solid;
  VolumeVisibility volume_visibility;
  json volumes_report = {{"on", plan.volumes.on}};
  if (plan.volumes.on) {
    phases.start("volumes");
    const std::string key = volume_key(scene, volume_settings);
    const std::string previous = s.output + "/extinction.vdb";
    bool reused = false;
    if (std::filesystem::exists(previous)) {
      try {
        ExtinctionGrid old = ExtinctionGrid::read(previous);
        if (old.metadata("geometry_key") == key) {
          grid = std::move(old);
          reused = true;
        }
      } catch (const InputError& e) {
        std::fprintf(stderr, "walkrad: warning: %s: not reused (%s)\n", previous.c_str(), e.what());
      }
    }
    if (!reused) grid = ExtinctionGrid::build(volume_clusters.boxes, ExtinctionGrid::choose_voxel_size(volume_clusters.boxes));
    grid.write(out.path("extinction.vdb"), {{"geometry_key", key},
                                           {"volume_clusters", std::to_string(volume_clusters.boxes.size())},
                                           {"volume_polygons", std::to_string(volume_clusters.volume_polygons)},
                                           {"min_polygons", std::to_string(volume_settings.min_polygons)},
                                           {"feature_ratio", json(volume_settings.feature_ratio).dump()},
                                           {"penumbra_ratio", json(volume_settings.penumbra_ratio).dump()}});
    solid = std::make_unique<RayScene>(scene, volume_clusters.polygon_in_volume);
    volume_visibility = {&volume_clusters, &grid, solid.get(), volume_settings.penumbra_ratio};
    const ExtinctionGrid::Stats gs = grid.stats();
    volumes_report = {{"on", true}, {"grid", reused ? "reused" : "built"}, {"file", "extinction.vdb"},
                      {"clusters", volume_clusters.boxes.size()}, {"polygons", volume_clusters.volume_polygons},
                      {"voxel_size_m", gs.voxel_size}, {"active_voxels", gs.active_voxels}, {"kappa_max", gs.kappa_max},
                      {"min_polygons", volume_settings.min_polygons}, {"feature_ratio", volume_settings.feature_ratio},
                      {"penumbra_ratio", volume_settings.penumbra_ratio}};
  }
  const MethodResult result = s.method == "classic"
                                  ? solve_classic(s, scene, rays, tree, bounds, plan, phases)
                                  : solve_hierarchical(s, scene, rays, tree, views, plan, twins,
                                                       plan.volumes.on ? &volume_visibility : nullptr, phases);

  phases.start("exposure");
  uint64_t exposure_rays = 0;
  double exposure = s.exposure;
  if (exposure <= 0) {
    exposure = auto_exposure(
        views, rays, 64, result.radiosity_at,
        [&](uint32_t poly) { return scene.materials[scene.polygons[poly].material].emits(); }, exposure_rays);
    if (views.empty()) exposure = result.surface_exposure;
  }

  phases.start("mesh");
  const SurfaceMesh surface = result.mesh(exposure);

  phases.start("chunks");
  ChunkCut cut = cut_into_chunks(surface, tree, s.chunk_triangles);
  for (ChunkMesh& m : cut.meshes) optimize_chunk(m);
  ChunkEncoding encoding;
  if (s.compress) {
    // One grid for every chunk (borders quantise alike). White on screen is B = π / exposure.
    float radiosity_max = 0;
    for (float b : surface.mesh.radiosity) radiosity_max = std::max(radiosity_max, b);
    encoding = draco_encoding(surface.mesh.bounds(), s.position_tolerance * length(bounds.diagonal()), radiosity_max,
                              s.radiosity_tolerance * kPi / exposure);
  }
  uint64_t chunk_rays = 0;
  // Fine enough that a sliver of a chunk seen through a doorway is not missed (a runtime would leave it
  // unloaded): up to 128² rays a view, about 4 million rays in all for long walkthroughs.
  const int chunk_grid = std::clamp(int(std::sqrt(4.0e6 / double(std::max<size_t>(views.size(), 1)))), 32, 128);
  const auto importance = chunk_importance(views, rays, cut.polygon_chunk, cut.meshes.size(), chunk_grid, chunk_rays);

  phases.start("write");
  Manifest manifest;
  manifest.tool = std::string("walkrad ") + WALKRAD_VERSION;
  manifest.scene_file = s.scene;
  manifest.scene_hash = hash_file(s.scene);
  manifest.bounds = surface.mesh.bounds();
  manifest.exposure = exposure;
  manifest.viewpoints = views;
  manifest.settings = s.to_json();
  manifest.effects = plan.to_json();
  for (size_t c = 0; c < cut.meshes.size(); ++c) {
    char name[32];
    std::snprintf(name, sizeof name, "chunk-%04zu.glb", c);
    ChunkInfo chunk;
    chunk.file = name;
    chunk.bounds = cut.meshes[c].bounds();
    chunk.triangles = cut.meshes[c].triangle_count();
    chunk.bytes = write_chunk(out.path(chunk.file), cut.meshes[c], encoding);
    chunk.importance = importance[c];
    manifest.chunks.push_back(chunk);
  }
  write_json(out.path("manifest.json"), manifest_to_json(manifest));
  phases.finish();

  const double seconds = std::chrono::duration<double>(Clock::now() - t_start).count();
  json counts = result.counts;
  counts["input_polygons"] = input.polygons.size();
  counts["polygons"] = scene.polygons.size();
  counts["contact_cuts"] = split_stats.cuts;
  counts["exposure_rays"] = exposure_rays;
  counts["triangles"] = surface.mesh.triangle_count();
  counts["chunks"] = cut.meshes.size();
  counts["chunk_importance_rays"] = chunk_rays;
  counts["viewpoints"] = views.size();
  counts["dropped_degenerate"] = input.dropped_degenerate;
  json report = {
      {"format", "walkrad-report"}, {"version", 1},   {"method", s.method},        {"threads", threads},
      {"phases", phases.list()},    {"total_seconds", seconds}, {"counts", counts}, {"solver", result.solver},
      {"energy", result.energy},    {"energy_audit", result.audit}, {"warnings", input.warnings}, {"effects", plan.to_json()},
      {"volumes", volumes_report},
  };
  write_json(out.path("report.json"), report);
  out.commit();

  BakeSummary summary;
  summary.output = s.output;
  summary.elements = result.counts.value("elements", uint64_t(0));
  summary.triangles = surface.mesh.triangle_count();
  summary.viewpoints = views.size();
  summary.exposure = exposure;
  summary.seconds = seconds;
  return summary;
}

}  // namespace walkrad
