#include "walkrad/bake/bake.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include "bake_inputs.h"
#include "checkpoint_file.h"
#include "method_run.h"
#include "prepared_scene.h"
#include "walkrad/formats/chunk_writer.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/manifest.h"
#include "walkrad/formats/walkthrough.h"
#include "walkrad/core/ranks.h"
#include "walkrad/core/file_hash.h"
#include "walkrad/core/staged_output.h"
#include "walkrad/output/chunk_optimizer.h"
#include "walkrad/output/chunking.h"
#include "walkrad/plan/effect_plan.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/scene/contact_split.h"
#include "walkrad/scene/scene_cleanup.h"
#include "walkrad/scene/transmission_twins.h"
#include "walkrad/visibility/exposure.h"
#include "walkrad/visibility/extinction_grid.h"
#include "walkrad/visibility/volume_visibility.h"

#ifndef WALKRAD_VERSION
#define WALKRAD_VERSION "0.0.0"
#endif

namespace walkrad {

using namespace bake_detail;

namespace {

void write_json(const std::string& path, const json& j) {
  std::ofstream out(path, std::ios::binary);
  out << j.dump(2) << '\n';
  if (!out) throw OutputError(path + ": cannot write");
}

// Settings that name a combination no method runs: refused before anything is read.
void check_method_settings(const BakeSettings& s) {
  const bool classic = s.method == Method::classic;
  if (!s.checkpoint.empty() && classic)
    throw InputError("--checkpoint", s.checkpoint, "checkpoints save the hierarchical method's solve (the classic method has no rounds)",
                     kExitBadArguments);
  if (s.solver == Iteration::southwell && !classic)
    throw InputError("--solver", "southwell", "progressive refinement shoots through the classic method's form factor matrix (use --method classic)",
                     kExitBadArguments);
  if (s.form_factors == FormFactors::hemicube && !classic)
    throw InputError("--form-factors", "hemicube", "the hemicube computes the classic method's matrix (use --method classic)",
                     kExitBadArguments);
  if (s.solver == Iteration::jacobi && classic)
    throw InputError("--solver", "jacobi", "the classic method solves by Gauss-Seidel or southwell", kExitBadArguments);
}

void require_emitter(const Scene& input, const std::string& file) {
  bool any_emitter = false;
  for (const Polygon& p : input.polygons) any_emitter = any_emitter || input.materials[p.material].emits();
  for (const PunctualLight& l : input.lights) any_emitter = any_emitter || max_component(l.intensity) > 0;
  if (!any_emitter)
    throw InputError(file, "", "the scene has no emitter (no material with emission, no punctual light): nothing to bake");
}

// The "exposure" phase: --exposure, else from the walkthrough's views (exposure.h), else from the surfaces.
double choose_exposure(const BakeSettings& s, const PreparedScene& p, const std::vector<Viewpoint>& views,
                       const MethodResult& result, uint64_t& exposure_rays) {
  if (s.exposure > 0) return s.exposure;
  const double exposure = auto_exposure(
      views, p.rays, 64, result.radiosity_at,
      [&](uint32_t poly) { return p.scene.materials[p.scene.polygons[poly].material].emits(); }, exposure_rays);
  return views.empty() ? result.surface_exposure : exposure;
}

// The "chunks" and "write" phases' output: the mesh cut into chunks, each optimised, encoded and
// written, and the manifest that lists them.
struct WrittenChunks {
  size_t count = 0;
  uint64_t importance_rays = 0;
};
WrittenChunks write_chunks(const BakeSettings& s, const BakeInputs& inputs, const PreparedScene& p, const Bounds& bounds,
                           const SurfaceMesh& surface, double exposure, StagedOutput& out, Phases& phases) {
  const std::vector<Viewpoint>& views = inputs.views;
  ChunkCut cut = cut_into_chunks(surface, p.tree, s.chunk_triangles);
  for (ChunkMesh& m : cut.meshes) optimize_chunk(m);
  ChunkEncoding encoding;
  if (s.compress) {
    // One grid for every chunk (borders quantise alike). White on screen is B = π / exposure.
    float radiosity_max = 0;
    for (float b : surface.mesh.radiosity) radiosity_max = std::max(radiosity_max, b);
    encoding = draco_encoding(surface.mesh.bounds(), s.position_tolerance * length(bounds.diagonal()), radiosity_max,
                              s.radiosity_tolerance * kPi / exposure);
  }
  WrittenChunks written;
  written.count = cut.meshes.size();
  // Fine enough that a sliver of a chunk seen through a doorway is not missed (a runtime would leave it
  // unloaded): up to 256² rays a view, about 16 million rays in all for long walkthroughs.
  const int chunk_grid = std::clamp(int(std::sqrt(1.6e7 / double(std::max<size_t>(views.size(), 1)))), 32, 256);
  const auto importance = chunk_importance(views, p.rays, cut.polygon_chunk, cut.meshes.size(), chunk_grid, written.importance_rays);

  phases.start("write");
  Manifest manifest;
  manifest.tool = std::string("walkrad ") + WALKRAD_VERSION;
  manifest.scene_file = s.scene;
  manifest.scene_hash = inputs.scene_hash;
  manifest.bounds = surface.mesh.bounds();
  manifest.exposure = exposure;
  manifest.viewpoints = views;
  manifest.settings = s.to_json();
  manifest.effects = p.plan.to_json();
  // Each chunk encoded (Draco) and written on its own, so in parallel: the same files, and the manifest
  // lists them in order (5.3 s on one thread for the 150-room level's chunks).
  manifest.chunks.resize(cut.meshes.size());
  tbb::parallel_for(size_t(0), cut.meshes.size(), [&](size_t c) {
    char name[32];
    std::snprintf(name, sizeof name, "chunk-%04zu.glb", c);
    ChunkInfo& chunk = manifest.chunks[c];
    chunk.file = name;
    chunk.bounds = cut.meshes[c].bounds();
    chunk.triangles = cut.meshes[c].triangle_count();
    chunk.bytes = write_chunk(out.path(chunk.file), cut.meshes[c], encoding);
    chunk.importance = importance[c];
  });
  write_json(out.path("manifest.json"), manifest_to_json(manifest));
  return written;
}

// Under mpirun (walkrad/core/ranks.h): every rank's share of the divided work, and its balance: the
// busiest rank's compute time over the mean (1: even). A collective call, made by every rank.
json ranks_report() {
  json per_rank = json::array();
  double busiest = 0, mean = 0;
  const std::vector<RankWork> work = all_rank_work();
  for (size_t r = 0; r < work.size(); ++r) {
    per_rank.push_back({{"rank", r}, {"items", work[r].items}, {"links", work[r].links}, {"rays", work[r].rays},
                        {"compute_seconds", work[r].compute_seconds}, {"exchange_seconds", work[r].exchange_seconds},
                        {"bytes_sent", work[r].bytes_sent}, {"peak_memory_mb", work[r].peak_memory_mb},
                        {"links_held", work[r].links_held}, {"link_mb_peak", double(work[r].link_bytes_peak) / double(1 << 20)}});
    busiest = std::max(busiest, work[r].compute_seconds);
    mean += work[r].compute_seconds / double(work.size());
  }
  return {{"count", ranks().size}, {"balance", mean > 0 ? busiest / mean : 1.0},
          {"bytes_exchanged", ranks_bytes_exchanged()}, {"per_rank", per_rank}};
}

}  // namespace

json BakeSettings::to_json() const {
  json j = {{"method", method_name(method)}, {"solver", iteration_name(solver)}, {"error", error}, {"view_independent", view_independent},
          {"min_area", min_area}, {"element_size", element_size}, {"form_factors", form_factors_name(form_factors)}, {"hemicube_resolution", hemicube_resolution},
          {"rays", rays_per_point}, {"exposure", exposure},
          {"tolerance", tolerance}, {"max_iterations", max_iterations}, {"chunk_triangles", chunk_triangles},
          {"compress", compress}, {"position_tolerance", position_tolerance}, {"radiosity_tolerance", radiosity_tolerance},
          {"effects", effects}, {"volume_min_polygons", volume_min_polygons}, {"volume_penumbra_ratio", volume_penumbra_ratio}};
  if (mgf_sides != 1) j["mgf_sides"] = mgf_sides;  // recorded where it departs from the default (older manifests the same)
  if (!sky.empty()) j["sky"] = sky;
  if (!up.empty()) j["up"] = up;
  if (!sun.empty()) j["sun"] = sun;
  return j;
}

double quality_error(Quality quality) {
  // The presets light bakers offer, as the refinement's tolerance relative to what each surface shows
  // (at medium, the default, about 1% weighted RMS on the Cornell box and 2% in office-floor's visited
  // rooms, a twentieth and a tenth of it).
  switch (quality) {
    case Quality::draft: return kDraftError;
    case Quality::medium: return kMediumError;
    case Quality::high: return kHighError;
    case Quality::final: return kFinalError;
  }
  return kMediumError;
}

const char* iteration_name(Iteration iteration) {
  return iteration == Iteration::jacobi ? "jacobi" : iteration == Iteration::southwell ? "southwell" : "gauss-seidel";
}

const char* form_factors_name(FormFactors form_factors) { return form_factors == FormFactors::hemicube ? "hemicube" : "contour"; }

Iteration parse_iteration(const std::string& word) {
  if (word == "gauss-seidel") return Iteration::gauss_seidel;
  if (word == "jacobi") return Iteration::jacobi;
  if (word == "southwell") return Iteration::southwell;
  throw InputError("--solver", word, "unknown solver (available: gauss-seidel, jacobi, southwell)", kExitBadArguments);
}

FormFactors parse_form_factors(const std::string& word) {
  if (word == "contour") return FormFactors::contour;
  if (word == "hemicube") return FormFactors::hemicube;
  throw InputError("--form-factors", word, "unknown form factors (available: contour, hemicube)", kExitBadArguments);
}

Quality parse_quality(const std::string& word) {
  if (word == "draft") return Quality::draft;
  if (word == "medium") return Quality::medium;
  if (word == "high") return Quality::high;
  if (word == "final") return Quality::final;
  throw InputError("--quality", word, "unknown quality (available: draft, medium, high, final)", kExitBadArguments);
}

BakeSummary bake(const BakeSettings& s) {
  const auto t_start = Clock::now();
  check_method_settings(s);
  std::unique_ptr<tbb::global_control> limit;
  if (s.threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(s.threads));
  const int threads = s.threads > 0 ? s.threads : tbb::info::default_concurrency();

  const CapWatch caps(s.caps, s.scene);
  Phases phases(s.progress, caps);
  phases.start("read");
  BakeInputs inputs = read_bake_inputs(s);  // under mpirun, read by rank 0 and sent to the others
  const Scene& input = inputs.scene;
  const std::vector<Viewpoint>& views = inputs.views;
  if (ranks().rank == 0)
    for (const std::string& w : input.warnings) std::fprintf(stderr, "walkrad: warning: %s: %s\n", s.scene.c_str(), w.c_str());
  const CheckpointFile checkpoint(s, inputs.scene_hash, inputs.views_hash);
  if (!s.checkpoint.empty()) checkpoint.check_writable();  // before the long work, not after a round
  require_emitter(input, s.scene);
  // Fail on an unwritable destination before the long work, not after it.
  StagedOutput out(s.output);

  phases.start("prepare");
  const Bounds bounds = input.bounds();
  const PreparedScene prepared(inputs, s);
  const EffectPlan& plan = prepared.plan;
  if (s.explain) std::printf("walkrad: effect plan for %s:\n%s", s.scene.c_str(), plan.explain().c_str());
  BakeVolumes volumes;
  volumes.report = {{"on", plan.volumes.on}};
  if (plan.volumes.on) {
    phases.start("volumes");
    build_volumes(prepared, s.output, out, volumes);
  }
  const Scene& scene = prepared.scene;
  MethodResult result = s.method == Method::classic
                            ? run_classic(s, scene, prepared.rays, prepared.tree, bounds, plan, phases)
                            : run_hierarchical(s, scene, prepared.rays, prepared.tree, views, plan, prepared.twins,
                                               plan.volumes.on ? &volumes.visibility : nullptr, checkpoint, phases);

  phases.start("exposure");
  uint64_t exposure_rays = 0;
  const double exposure = choose_exposure(s, prepared, views, result, exposure_rays);

  phases.start("mesh");
  json mesh_counts = json::object();
  const SurfaceMesh surface = result.mesh(exposure, mesh_counts, result.solver);

  phases.start("chunks");
  const WrittenChunks chunks = write_chunks(s, inputs, prepared, bounds, surface, exposure, out, phases);
  phases.finish();

  const double seconds = std::chrono::duration<double>(Clock::now() - t_start).count();
  json counts = result.counts;
  counts.update(mesh_counts);
  counts["input_polygons"] = prepared.input_polygons;
  counts["polygons"] = scene.polygons.size();
  counts["contact_cuts"] = prepared.split_stats.cuts;
  counts["covered_pieces"] = prepared.split_stats.covered;
  counts["exposure_rays"] = exposure_rays;
  counts["triangles"] = surface.mesh.triangle_count();
  counts["chunks"] = chunks.count;
  counts["chunk_importance_rays"] = chunks.importance_rays;
  counts["viewpoints"] = views.size();
  counts["dropped_degenerate"] = input.dropped_degenerate;
  json report = {
      {"format", "walkrad-report"}, {"version", 1},   {"method", method_name(s.method)},        {"threads", threads},
      {"phases", phases.list()},    {"total_seconds", seconds}, {"counts", counts}, {"solver", result.solver},
      {"energy", result.energy},    {"energy_audit", result.audit}, {"warnings", input.warnings}, {"effects", plan.to_json()},
      {"volumes", volumes.report},  {"ranks", ranks_report()},
  };
  write_json(out.path("report.json"), report);
  out.commit();
  if (!s.checkpoint.empty()) checkpoint.remove();  // the bake is written: nothing left to resume

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
