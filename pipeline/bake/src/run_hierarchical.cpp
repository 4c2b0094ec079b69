// The hierarchical method's run inside a bake (bake.cpp): importance, the refine-solve rounds with
// progress, the error left per stretch of the walkthrough, the audit.
#include <algorithm>
#include <functional>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include "method_run.h"
#include "walkrad/core/free_memory.h"
#include "walkrad/core/progress.h"
#include "walkrad/core/ranks.h"
#include "walkrad/formats/error.h"
#include "walkrad/hierarchical/display_refinement.h"
#include "walkrad/hierarchical/estimated_error.h"
#include "walkrad/hierarchical/final_gather.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy_audit.h"
#include "walkrad/hierarchical/link_owners.h"
#include "walkrad/hierarchical/link_transport.h"
#include "walkrad/hierarchical/view_importance.h"
#include "walkrad/output/hierarchy_mesher.h"
#include "walkrad/visibility/exposure.h"

namespace walkrad::bake_detail {

namespace {

// The hierarchical solve's sweeps stop at this share of the requested error at the latest (--tolerance
// asks for less only where it is larger).
constexpr double kSweepShareOfError = 5e-3;

// estimate_error (estimated_error.h) as report.json writes it.
json error_estimate(const Hierarchy& h, const std::vector<ViewHit>& hits, size_t view_count) {
  const EstimatedError e = estimate_error(h, hits, view_count);
  json out = {{"measure", "relative RMS of luminance, weighted by solid angle (as walkrad sweep's rms_weighted)"},
              {"overall", e.overall}};
  if (!e.over_views) {
    out["over"] = "surfaces, by area (no viewpoints)";
    return out;
  }
  json per = json::array();
  for (const EstimatedError::Segment& k : e.segments)
    per.push_back({{"first_view", k.first_view}, {"last_view", k.last_view}, {"estimated_error", k.error}});
  out["over"] = "the walkthrough's primary-ray hits";
  out["segments"] = per;
  return out;
}

// The solver's settings from the bake's and the effect plan (hierarchical_solver.h). gathered: the
// polygons the walkthrough sees, where the final gather evaluates direct light (null: all of them).
HierarchicalSettings solver_settings(const BakeSettings& s, const Scene& scene, const EffectPlan& plan,
                                     const std::vector<uint32_t>& twins, const VolumeVisibility* volumes,
                                     const std::vector<uint8_t>* gathered, Phases& phases) {
  HierarchicalSettings hs;
  hs.error = s.error;
  hs.min_area = s.min_area;
  hs.rays = std::max(1, s.rays_per_point) * 16;
  // Sweeps stop where no leaf moves by more than 1/200 of the error asked for: what is left after
  // them, about the last update × g/(1 − g) for a gain g a sweep (0.85–0.90 in the tail of office-floor
  // 32 rooms' last round: 8 times it, 4% of the error), is far below what the refinement leaves. A
  // thousandth would cost sweeps for nothing: 32 rooms' last round takes 34 sweeps to reach it, and
  // the 8-room level (11 sweeps against 15) and the 150-room one (12 against 14) measure the same RMS
  // error against their references at both, to every digit.
  hs.tolerance = std::max({s.tolerance, 1e-6, kSweepShareOfError * s.error});
  hs.gauss_seidel = s.solver == Iteration::gauss_seidel;
  hs.visibility = plan.visibility.on;
  hs.indirect = plan.indirect.on;
  hs.closed = plan.closure.on;
  hs.closed_rows = plan.closed && !(plan.closure.forced && !plan.closure.on);  // closure=off: no scaling at all
  if (plan.punctual.on) hs.lights = &scene.lights;
  hs.gather = plan.gather.on;
  hs.gathered = gathered;
  if (plan.transmission.on) hs.twins = &twins;
  hs.volumes = volumes;
  hs.ray_sample = s.ray_sample;
  hs.check_limits = [&phases](const char* where, uint64_t more) {
    phases.check(std::string("solve: ") + where);
    if (more > 0)
      phases.check_predicted(std::string("solve: ") + where, resident_memory_mb() + (more >> 20),
                             "the list of new links (" + std::to_string(more >> 20) + " MiB more)");
  };
  return hs;
}

// Checkpoints: the state after each round, and a bake resumed from the last one saved. Returns the
// rounds read back (0: none); resume_state holds the bytes hs.resume reads.
int attach_checkpoint(const BakeSettings& s, const CheckpointFile& checkpoint, HierarchicalSettings& hs,
                      std::unique_ptr<ByteReader>& resume_state) {
  if (s.checkpoint.empty()) return 0;
  int resumed_rounds = 0;
  if (s.resume && checkpoint.open(resumed_rounds, resume_state)) {
    hs.resume = resume_state.get();
    if (s.progress)
      std::fprintf(stderr, "walkrad: resuming the solve after round %d (%s)\n", resumed_rounds, checkpoint.path().c_str());
  } else if (s.resume && s.progress) {
    std::fprintf(stderr, "walkrad: no checkpoint in %s: solving from the start\n", s.checkpoint.c_str());
  }
  hs.save_round = [&checkpoint](int rounds, const std::function<void(ByteWriter&)>& write_state) {
    checkpoint.write(rounds, write_state);
  };
  return resumed_rounds;
}

// Called after each round of the solve: checks the caps (memory predicted for the next round), keeps
// the round's wall time and prints the progress line.
class RoundReporter {
 public:
  RoundReporter(const HierarchicalStats& stats, Phases& phases, bool progress)
      : stats_(stats), phases_(phases), progress_(progress), t0_(Clock::now()), round_start_(t0_),
        start_rss_(resident_memory_mb()), previous_rss_(start_rss_) {}

  void operator()(const IterationStats& it) {
    const std::string round = std::to_string(stats_.iterations.size());
    phases_.check("solve round " + round);
    // Memory, predicted: the next round adds links at the rate the last two rounds' additions
    // changed by, and memory with them (links and elements grow together).
    const uint64_t rss = resident_memory_mb();
    if (previous_new_ > 0 && it.new_links > 0 && rss > previous_rss_) {
      // At most as many as the last round: the first rounds multiply their links by 100 and more,
      // a rate no bake keeps, and the Cornell box's default bake, whose additions went ×2.3 from its
      // 4th to its 5th round, then added half as many (a ratio kept would have predicted 343 MiB
      // for its 197). A faster growth is caught within the round (HierarchicalSettings::check_limits).
      const double growth = std::min(1.0, double(it.new_links) / double(previous_new_));
      const auto predicted = uint64_t(double(rss) + double(rss - previous_rss_) * growth);
      phases_.check_predicted("solve round " + round, predicted,
                              "solve round " + std::to_string(stats_.iterations.size() + 1) + " (" +
                                  std::to_string(it.links) + " links, +" + std::to_string(it.new_links) + " in the last round)");
    }
    previous_rss_ = rss;
    const auto now = Clock::now();
    round_seconds_.push_back(std::chrono::duration<double>(now - round_start_).count());
    const double left = refinement_seconds_left(previous_new_, it.new_links, round_seconds_.back());
    previous_new_ = it.new_links;
    round_start_ = now;
    if (!progress_) return;
    char eta[64] = "remaining unknown", estimate[48] = "";
    // While the wave of new links grows (left unknown) or where it says more: the cap that stops the
    // bake if refinement does not end first, a number from the first round on.
    const double solved = std::chrono::duration<double>(now - t0_).count();
    const double to_memory = seconds_to_memory_cap(phases_.caps().memory_cap_mb(), start_rss_, rss, solved);
    const double to_time = phases_.caps().seconds_left();
    const bool time_first = to_time >= 0 && (to_memory < 0 || to_time <= to_memory);
    const double bound = time_first ? to_time : to_memory;
    if (left >= 0 && (bound < 0 || left <= bound)) std::snprintf(eta, sizeof eta, "about %.0f s left", left);
    else if (bound >= 0) std::snprintf(eta, sizeof eta, "at most ~%.0f s left (%s)", bound, time_first ? "--max-seconds" : "the memory cap");
    if (it.estimated_error >= 0) std::snprintf(estimate, sizeof estimate, ", estimated error %.2f%%", 100 * it.estimated_error);
    std::fprintf(stderr, "walkrad: solve round %zu: %llu links (+%llu), %llu elements, change %.2e%s, %.1f s, %s\n",
                 stats_.iterations.size(), static_cast<unsigned long long>(it.links),
                 static_cast<unsigned long long>(it.new_links), static_cast<unsigned long long>(it.elements), it.change,
                 estimate, solved, eta);
    if (stats_.stalled_round + 1 == int64_t(stats_.iterations.size()) && stats_.iterations.size() >= 3) {
      const IterationStats& before = stats_.iterations[stats_.iterations.size() - 3];
      std::fprintf(stderr,
                   "walkrad: refinement stops: rounds %zu to %zu multiplied the links by %.1f for %.0f%% less estimated "
                   "error (diminishing returns); the next round converges the links there are\n",
                   stats_.iterations.size() - 2, stats_.iterations.size(), double(it.links) / double(before.links),
                   100 * (1 - it.estimated_error / before.estimated_error));
    }
  }

  // The wall time of each round run here (the rounds a resumed bake read back come first and have none):
  // the rounds against their rays show where the solve's own work is.
  const std::vector<double>& round_seconds() const { return round_seconds_; }

 private:
  const HierarchicalStats& stats_;
  Phases& phases_;
  bool progress_;
  Clock::time_point t0_, round_start_;
  uint64_t start_rss_, previous_new_ = 0, previous_rss_;
  std::vector<double> round_seconds_;
};

// The adaptive output mesh (final_gather.h): gathered leaves split where Gouraud shading would miss
// a shadow's edge, the worst first, within an eighth as many new leaves as the solution has, at
// least 2,048. Without it a 5 cm penumbra is 13% off; with it 4.2%, and 2.4% with 32² points per
// penumbra vertex (test ContactShadow). As the discontinuity cuts put penumbrae's edges on element
// edges, the floor buys little: 2,048 against 4,096 gives that penumbra 0.96% against 0.88% (lit
// floor 0.70%), the Cornell box 0.870% both, lamp-room 1.291% against 1.288%, for 1.41× the chunk
// bytes of a bake without the gather instead of 1.63× and 1.73× (the gather is allowed 1.5×). Half
// as many leaves as the solution costs office-floor 84 s of CPU, not 75.
DisplayRefinement display_refinement(const BakeSettings& s, const EffectPlan& plan, const HierarchicalSettings& hs,
                                     const HierarchicalStats& stats, const Hierarchy& h) {
  DisplayRefinement refinement;
  refinement.seen = hs.gathered;
  refinement.ungathered = !plan.importance.on;  // every surface is what the display shows
  refinement.twins = hs.twins;
  refinement.error = s.error;
  refinement.white = stats.white;
  refinement.min_area = stats.min_area / 64;  // three levels below the solution's finest: a penumbra is narrow
  refinement.max_depth = hs.max_depth;
  refinement.budget = std::max<uint64_t>(h.element_count() / 8, 2048);
  return refinement;
}

// report.json's solver entry: the rounds, the oracle, convergence, the closure balance.
json solver_report(const BakeSettings& s, const HierarchicalSettings& hs, const HierarchicalStats& stats,
                   const std::vector<double>& round_seconds, int resumed_rounds) {
  json rounds = json::array();
  const size_t read_back = stats.iterations.size() - round_seconds.size();
  for (size_t k = 0; k < stats.iterations.size(); ++k) {
    const IterationStats& it = stats.iterations[k];
    rounds.push_back({{"links", it.links}, {"new_links", it.new_links}, {"sweeps", it.sweeps}, {"elements", it.elements}, {"rays", it.rays},
                      {"seconds", k < read_back ? json(nullptr) : json(round_seconds[k - read_back])},
                      {"change", it.change}, {"emitted_w", vec_json(it.emitted)}, {"absorbed_w", vec_json(it.absorbed)},
                      {"residual_w", vec_json(it.residual)}, {"clamped_leaves", it.clamped_leaves},
                      {"bytes_exchanged", it.bytes_exchanged}, {"sweep_bytes", it.sweep_bytes},
                      {"estimated_error", it.estimated_error < 0 ? json(nullptr) : json(it.estimated_error)}});
  }
  return {{"iteration", iteration_name(s.solver)},
          {"oracle", stats.oracle}, {"error", s.error}, {"white", stats.white}, {"min_area", stats.min_area},
          {"above_tolerance", stats.above_tolerance},
          {"converged", stats.converged}, {"tolerance", hs.tolerance}, {"rounds", rounds},
          {"refinement_stalled_after_round", stats.stalled_round < 0 ? json(nullptr) : json(stats.stalled_round + 1)},
          {"resumed_after_round", resumed_rounds},
          {"links_divided", stats.divided},  // among ranks (walkrad/hierarchical/link_owners.h)
          {"link_mb_peak", double(stats.link_bytes_peak) / double(1 << 20)},  // this rank's
          {"corrections", stats.corrections},
          {"balance", {{"iterations", stats.balance_iterations}, {"row_error", stats.balance_row_error},
                       {"column_error", stats.balance_column_error}, {"unbalanced_leaves", stats.balance_unbalanced},
                       {"rows_only", hs.closed_rows && !hs.closed}, {"mean_raw_row_sum", stats.mean_row_sum}}}};
}

}  // namespace

MethodResult run_hierarchical(const BakeSettings& s, const Scene& scene, const RayScene& rays, const ClusterTree& tree,
                                const std::vector<Viewpoint>& views, const EffectPlan& plan, const std::vector<uint32_t>& twins,
                                const VolumeVisibility* volumes, const CheckpointFile& checkpoint, Phases& phases) {
  auto h = std::make_shared<Hierarchy>(scene, tree, plan.textures.on);
  uint64_t view_rays = 0;
  std::vector<ViewHit> hits;
  if (!views.empty()) {
    phases.start("importance");
    hits = cast_view_rays(views, rays, 128, 64, view_rays);
    if (plan.importance.on) h->set_view_hits(hits);
  }
  phases.start("solve");
  // The final gather at the polygons the walkthrough sees (all of them when forced on without viewpoints).
  auto seen = std::make_shared<std::vector<uint8_t>>();
  if (plan.gather.on && !hits.empty()) {
    seen->assign(scene.polygons.size(), 0);
    for (const ViewHit& hit : hits) (*seen)[hit.polygon] = 1;
  }
  HierarchicalSettings hs = solver_settings(s, scene, plan, twins, volumes, seen->empty() ? nullptr : seen.get(), phases);
  std::unique_ptr<ByteReader> resume_state;
  const int resumed_rounds = attach_checkpoint(s, checkpoint, hs, resume_state);
  // Over several ranks, say when every rank holds every link, and why (link_owners.h).
  if (ranks().size > 1 && ranks().rank == 0 && s.progress)
    if (const char* why = undivided_because(hs)) std::fprintf(stderr, "walkrad: every rank holds every link (%s)\n", why);
  // Each round's estimate: what the round's links bought, shown in the progress, and where more links stop
  // buying accuracy, the end of refinement (refinement_stalled).
  hs.estimate = [&] { return estimate_error(*h, hits, views.size()).overall; };
  HierarchicalStats stats;
  RoundReporter on_round(stats, phases, s.progress);
  try {
    solve_hierarchical(*h, rays, hs, stats, std::ref(on_round));
  } catch (const ByteFormatError& e) {  // only a resumed state is read as bytes
    throw InputError(checkpoint.path(), "", std::string("damaged checkpoint (") + e.what() + ")");
  }
  for (const HNode& n : h->nodes())
    if (!is_finite(n.B)) throw std::runtime_error("the solution is not finite (please report this scene)");

  MethodResult r;
  r.radiosity_at = [h](uint32_t poly, const Vec3& p) {
    // The element root of an input polygon: a leaf cluster's children, found through the tree.
    return (*h)[leaf_at(*h, h->polygon_root(poly), p)].B;
  };
  PointSolution point;
  point.on = true;
  point.indirect = plan.indirect.on;
  point.twins = plan.transmission.on ? &twins : nullptr;
  point.lights = plan.punctual.on ? &scene.lights : nullptr;
  point.rays = plan.visibility.on ? &rays : nullptr;
  point.gather = plan.gather.on;
  point.seen = hs.gathered;
  point.discontinuities = plan.discontinuities.on;
  point.position_error = s.position_tolerance;
  const DisplayRefinement refinement = display_refinement(s, plan, hs, stats, *h);
  const auto* lights = hs.lights;
  const RayScene* occluders = plan.visibility.on ? &rays : nullptr;
  // The estimate is made once the output mesh is refined (the leaves' interpolation error is in it).
  auto view_hits = std::make_shared<std::vector<ViewHit>>(std::move(hits));
  const size_t view_count = views.size();
  r.mesh = [h, point, seen, refinement, lights, occluders, view_hits, view_count, &phases](double exposure, json& counts,
                                                                                           json& solver) {
    if (point.gather || refinement.ungathered) {
      phases.start(point.gather ? "gather" : "display");
      uint64_t gather_rays = 0;
      std::optional<DirectGather> gather;
      if (point.gather) gather.emplace(*h, lights, occluders);
      const uint64_t splits = refine_display(*h, gather ? &*gather : nullptr, refinement, gather_rays);
      counts[point.gather ? "gather_splits" : "display_splits"] = splits;
      if (point.gather) counts["gather_test_rays"] = gather_rays;
      phases.start("mesh");
    }
    solver["estimated_error"] = error_estimate(*h, *view_hits, view_count);
    PointSolution drawn = point;
    PointSolution::Counts boundaries;
    drawn.counts = &boundaries;
    // The output stage adds no links and reads each where it is (link_owners.h): noted, so that a rank's
    // link_mb_peak covers the whole bake.
    rank_work().link_bytes_peak = std::max(rank_work().link_bytes_peak, link_bytes(*h));
    // Read, the links are spent (nothing after the mesh reads them): the 150-room level's 16 M links
    // freed before its 3.7 M-triangle mesh is written.
    drawn.read = [h] {
      for (HNode& n : h->nodes()) std::vector<Link>().swap(n.links);
      release_free_memory();
    };
    SurfaceMesh mesh = mesh_hierarchy(*h, exposure, drawn);
    if (point.discontinuities)
      counts["shadow_boundaries"] = {{"found", boundaries.found}, {"hidden", boundaries.hidden}, {"drawn", boundaries.drawn},
                                     {"faces_cut", boundaries.faces_cut},
                                     {"contact_bands", boundaries.contact_bands}};
    return mesh;
  };
  std::vector<double> lum;
  for (const HNode& n : h->nodes())
    if (!n.cluster && !n.child_count && !n.emission.x && !n.emission.y && !n.emission.z) lum.push_back(luminance(n.B) / kPi);
  r.surface_exposure = exposure_for(std::move(lum));
  r.counts = {{"elements", h->element_count()}, {"links", stats.links}, {"refinements", stats.refinements}, {"receiver_splits", stats.receiver_splits}, {"recast_links", stats.recast}, {"proven_hidden_links", stats.proven_hidden},
              {"probed_pairs", stats.probed_pairs}, {"probe_hidden_pairs", stats.probe_hidden}, {"probe_rays", stats.probe_rays},
              {"unoccluded_links", stats.unoccluded_links}, {"exact_links", stats.exact_links},
              {"volume_links", stats.volume_links}, {"grid_segments", stats.grid_segments},
              {"monte_carlo_links", stats.monte_carlo_links},
              {"visibility_rays", stats.rays}, {"importance_rays", view_rays}, {"iterations", stats.iterations.size()},
              {"light_rays", stats.light_rays}, {"light_refinements", stats.light_refinements}};
  r.solver = solver_report(s, hs, stats, on_round.round_seconds(), resumed_rounds);
  const IterationStats& last = stats.iterations.back();
  r.energy = energy_json(last.emitted, last.absorbed);
  r.energy["residual_w"] = vec_json(last.residual);
  r.audit = audit_json(audit_hierarchy(*h, plan.transmission.on ? &twins : nullptr));
  return r;
}

}  // namespace walkrad::bake_detail
