// The hierarchical method's run inside a bake (bake.cpp): importance, the refine-solve rounds with
// progress, the error left per stretch of the walkthrough, the audit.
#include <algorithm>
#include <memory>
#include <stdexcept>

#include "method_run.h"
#include "walkrad/core/progress.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy_audit.h"
#include "walkrad/hierarchical/view_importance.h"
#include "walkrad/output/hierarchy_mesher.h"
#include "walkrad/visibility/exposure.h"

namespace walkrad::bake_detail {

namespace {

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

}  // namespace

MethodResult run_hierarchical(const BakeSettings& s, const Scene& scene, const RayScene& rays, const ClusterTree& tree,
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
  hs.checkpoint = [&phases](const char* where, uint64_t more) {
    phases.check(std::string("solve: ") + where);
    if (more > 0)
      phases.check_predicted(std::string("solve: ") + where, resident_memory_mb() + (more >> 20),
                             "the list of new links (" + std::to_string(more >> 20) + " MiB more)");
  };
  HierarchicalStats stats;
  const auto t0 = Clock::now();
  auto round_start = t0;
  uint64_t previous_new = 0, previous_rss = resident_memory_mb();
  solve_hierarchical(*h, rays, hs, stats, [&](const IterationStats& it) {
    const std::string round = std::to_string(stats.iterations.size());
    phases.check("solve round " + round);
    // Memory, predicted: the next round adds links at the rate the last two rounds' additions
    // changed by, and memory with them (links and elements grow together).
    const uint64_t rss = resident_memory_mb();
    if (previous_new > 0 && it.new_links > 0 && rss > previous_rss) {
      // At most as many as the last round: the first rounds multiply their links by 100 and more,
      // a rate no bake keeps, and the Cornell box's default bake, whose additions went ×2.3 from its
      // 4th to its 5th round, then added half as many (a ratio kept would have predicted 343 MiB
      // for its 197). A faster growth is caught within the round (HierarchicalSettings::checkpoint).
      const double growth = std::min(1.0, double(it.new_links) / double(previous_new));
      const auto predicted = uint64_t(double(rss) + double(rss - previous_rss) * growth);
      phases.check_predicted("solve round " + round, predicted,
                             "solve round " + std::to_string(stats.iterations.size() + 1) + " (" +
                                 std::to_string(it.links) + " links, +" + std::to_string(it.new_links) + " in the last round)");
    }
    previous_rss = rss;
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

}  // namespace walkrad::bake_detail
