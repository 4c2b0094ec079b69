#include "walkrad/hierarchical/hierarchical_solver.h"

#include <algorithm>
#include <cmath>

#include "solver.h"
#include "walkrad/hierarchical/link_transport.h"

namespace walkrad {
namespace hierarchical_detail {

Solver::Solver(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& s, HierarchicalStats& stats)
      : h_(h), rays_(rays), s_(s), stats_(stats) {
  const HNode& root = h_[h_.root()];
  mark_two_sided_clusters();
  // Punctual lights first: what they deliver to the surfaces counts in the power Φ that scales ε.
  if (lights()) {  // every element is an input polygon's root here
    for (uint32_t i = 0; i < h_.nodes().size(); ++i)
      if (!h_[i].cluster) light_frontier_.push_back(i);
    light_spread_ = direct_for(light_frontier_);
  }
  Vec3 emitted;
  for (const HNode& n : h_.nodes())
    if (!n.cluster) emitted += (n.emission + n.D) * n.area;
  const double power = luminance(emitted);
  eps_ = s_.epsilon * power;
  stats_.epsilon_absolute = eps_;
  min_area_ = s_.min_area > 0 ? s_.min_area : std::pow(2.0 * root.radius / 256.0, 2);
  // Changes are measured relative to the leaf's radiosity, but not below 1e-9 of the brightest
  // emitter's: a closed dark room's last traces of light decay by ρ per sweep and would keep their
  // relative change until they underflow (3,853 sweeps in the junction scene).
  for (const HNode& n : h_.nodes())
    if (!n.cluster) change_floor_ = std::max(change_floor_, 1e-9 * max_component(n.emission + mul(n.rho, n.D)));
  // Importance: scaled so that Σ R = Σ A, then B·I·ρ·F and the BF oracle B·A·ρ·F share ε.
  importance_ = s_.use_importance && root.R > 0;
  stats_.oracle = importance_ ? "importance" : "BF";
  if (importance_) {
    const double scale = root.area / root.R;
    for (HNode& n : h_.nodes()) {
      n.R *= scale;
      n.I = n.R;
    }
  }
}

void Solver::run(const std::function<void(const IterationStats&)>& progress) {
  bool converged_before = false;
  for (int it = 0; it < s_.max_iterations; ++it) {
    IterationStats is;
    const size_t before = pending_.size();
    if (it == 0) {
      refine_for_lights();
      refine(h_.root(), h_.root(), nullptr);
    } else {
      refine_existing();
    }
    if (s_.checkpoint) s_.checkpoint("refinement", 0);
    if (lights()) compute_missing_direct();  // elements the refinement created
    is.new_links = pending_.size() - before;
    evaluate_pending(is);
    if (s_.checkpoint) s_.checkpoint("link evaluation", 0);
    if (s_.closed && is.new_links > 0) balance_closed();  // factors and B must match at the end
    const bool settled = is.new_links == 0;
    if (settled && converged_before) {
      is.change = 0;
      record(is, progress);
      stats_.converged = true;
      break;
    }
    const int sweeps = settled ? 1000 : s_.sweeps;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      ++is.sweeps;
      is.change = solve_sweep(is);
      if (s_.accelerate && s_.indirect && !s_.twins) {
        is.change = std::max(is.change, aggregation_correction(h_, change_floor_));
        ++stats_.corrections;
      }
      if (is.change <= s_.tolerance) break;
    }
    converged_before = is.change <= s_.tolerance;
    record(is, progress);
  }
  measure_left_error();
}

void Solver::balance_closed() {
  const BalanceStats b = balance_closed_transport(h_);
  stats_.balance_iterations += b.iterations;
  stats_.balance_row_error = b.row_error;
  stats_.balance_column_error = b.column_error;
  stats_.balance_unbalanced = b.unbalanced;
}

void Solver::record(IterationStats& is, const std::function<void(const IterationStats&)>& progress) {
  is.links = stats_.links;
  is.elements = h_.element_count();
  if (is.emitted == Vec3{} && !stats_.iterations.empty()) {  // no solve this round: keep the last
    is.emitted = stats_.iterations.back().emitted;
    is.absorbed = stats_.iterations.back().absorbed;
    is.residual = stats_.iterations.back().residual;
  }
  stats_.iterations.push_back(is);
  if (progress) progress(is);
}

void Solver::measure_left_error() {
  for (const HNode& n : h_.nodes())
    for (const Link& l : n.links) {
      const double e = luminance(h_[l.source].B) * weight(n) * luminance(n.rho) * l.F;
      stats_.left_error_max = std::max(stats_.left_error_max, e);
      stats_.left_error_sum += e;
    }
}

thread_local std::vector<double> Solver::kernel_scratch_;
thread_local std::vector<Solver::ClusterSample> Solver::cluster_scratch_;
thread_local std::vector<uint8_t> Solver::blocked_scratch_;

}  // namespace hierarchical_detail

void solve_hierarchical(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& settings, HierarchicalStats& stats,
                        const std::function<void(const IterationStats&)>& progress) {
  stats = {};
  if (h.nodes().empty()) return;
  hierarchical_detail::Solver solver(h, rays, settings, stats);
  solver.run(progress);
}

}  // namespace walkrad
