#include "walkrad/hierarchical/hierarchical_solver.h"

#include <algorithm>
#include <cmath>

#include "solver.h"

#include "walkrad/core/free_memory.h"
#include "walkrad/core/invariant.h"
#include "walkrad/hierarchical/hierarchy_invariants.h"
#include "walkrad/core/ranks.h"
#include "walkrad/hierarchical/link_transport.h"

namespace walkrad {
namespace hierarchical_detail {

Solver::Solver(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& s, HierarchicalStats& stats)
      : h_(h), rays_(rays), s_(s), stats_(stats), evaluator_(h, rays, s), typical_area_(default_min_area(h)),
        oracle_(h, s, typical_area_ * 16),  // quantum area: the median polygon side / 32, squared
        division_{!indivisible_because(s), ranks().size > 1 && !undivided_because(s)},
        refinement_(h, rays, s, stats, oracle_, division_, typical_area_),  // the punctual lights' D known
        sweeps_(h, s, oracle_, division_) {
  const HNode& root = h_[h_.root()];
  if (division_.divided) h_.owners() = divide_polygons(h_.tree(), ranks().size, ranks().rank);
  stats_.divided = division_.divided;
  sweeps_.measure_change_floor();  // the punctual lights' D known (the refinement's constructor)
  // Importance: scaled so that Σ R = Σ A. The display weight's unit is the importance density of a
  // surface the views see barely (the 10th percentile by area over the elements they see directly):
  // every pixel's error counts the same, so a far wall is held to the error of a near floor.
  const bool importance = s_.use_importance && root.R > 0;
  stats_.oracle = importance ? "importance" : "view-independent";
  if (importance) {
    // The hits themselves are scaled, not only the nodes' R: an element split later sums its hits'
    // weights, and unscaled (a 1/Σ A share) they would make a seen element lose its direct importance
    // once split (an office room's refined leaves would show 0.03 of their weight).
    h_.scale_view_hits(root.area / root.R);
    std::vector<std::pair<double, double>> seen;  // density, area
    double total = 0;
    for (HNode& n : h_.nodes()) {
      n.I = n.R;
      if (!n.cluster && n.R > 0 && n.area > 0) {
        seen.push_back({n.R / n.area, n.area});
        total += n.area;
      }
    }
    std::sort(seen.begin(), seen.end());
    double below = 0, seen_density = 0;
    for (const auto& [density, area] : seen) {
      seen_density = density;
      below += area;
      if (below >= ErrorOracle::kSeenQuantile * total) break;
    }
    oracle_.weigh_by_importance(seen_density);
  }
}

void Solver::run(const std::function<void(const IterationStats&)>& progress) {
  RoundState state;
  if (s_.resume) state = load_state(*s_.resume);
  exchanged_before_ = ranks_bytes_exchanged();  // the rounds' own exchanges, not reading the inputs
  bool& converged_before = state.converged_before;
  int last_round = -1;
  for (int it = state.next_round; !state.finished && it < s_.max_iterations; ++it) {
    last_round = it;
    IterationStats is;
    const uint64_t before = refinement_.new_link_count();
    const size_t elements_before = h_.element_count();
    if (it == 0) {
      if (oracle_.importance()) {  // the close-pair rule weighs by direct importance (close_matters)
        oracle_.state().direct_weights = true;
        oracle_.update_scales();
      }
      refinement_.refine_first();  // as high as links may go: the error is measured from round 1
    } else if (!state.stalled) {
      oracle_.state().direct_weights = it == 1;
      if (it == 1) {
        oracle_.update_scales();
        refinement_.refine_for_lights();
      }
      // The last round's estimate measured these from the same state (its weights too, past round 1).
      if (estimated_round_ != it - 1 || it < 3) {
        oracle_.update_scales();
        oracle_.measure_variation();
      }
      refinement_.refine_existing();
    }
    if (s_.check_limits) s_.check_limits("refinement", 0);
    // The refinement's lists, made by both threads: without this the 150-room level held 0.7 GB
    // more after its solve once its decisions were made in parallel.
    release_free_memory();
    if (lights()) refinement_.compute_missing_direct();  // elements the refinement created
    is.new_links = refinement_.new_link_count() - before;
    note_link_memory();
    evaluate_pending(is);
    release_free_memory();
    // Divided: the polygons dealt again by the links of the first rounds that link elements (the later
    // rounds refine where these are; the first deal, blind, left office-floor's 32 rooms 57/43%).
    if (division_.divided && it >= 1) rebalance_links(h_);
    note_link_memory();
    if (s_.check_limits) s_.check_limits("link evaluation", 0);
    if (s_.closed && is.new_links > 0) balance_closed();  // factors and B must match at the end
    if (s_.closed_rows && !s_.closed && is.new_links > 0) {
      const std::vector<uint8_t> unscaled = refinement_.under_close_pairs();
      stats_.balance_unbalanced = normalise_closed_rows(h_, &stats_.mean_row_sum, &unscaled);
    }
    const bool settled = is.new_links == 0 && h_.element_count() == elements_before;  // (lights split elements too)
    if (settled && converged_before) {
      is.change = 0;
      estimate_round(is, it);
      record(is, progress);
      stats_.converged = true;
      save_round(state, it, true);
      break;
    }
    // A round that added under 5% of the links is the last: each later round costs a pass over every
    // link and its sweeps for a few more (office3: 3 rounds for 2.9% of its links, and the same error).
    const bool last = settled || (it > 1 && is.new_links * kLastRoundShare < stats_.links);
    const int sweeps = last ? 1000 : s_.sweeps;
    const bool correct = s_.accelerate && s_.indirect && !s_.twins;
    int interval = 0, wait = 0;  // sweeps between corrections, and before the next one
    const uint64_t sweeps_from = ranks_bytes_exchanged();
    CorrectionBuffers buffers;  // the round's: given back before the next round's refinement
    if (s_.gauss_seidel) sweeps_.plan_gather_blocks();  // the links stay as they are through the round's sweeps
    // Over-relaxed in the last round only, once its first sweeps have taken up the new links (from a
    // round's first sweep the direct light would be overshot too), and not for Jacobi, whose modes of
    // eigenvalue −ρF it would drive apart. It starts after two plain sweeps past those, each of which
    // left at least kSlowSweep of the change before it: where the modes left are fast, ω > 1 makes them
    // oscillate with 1 − ω instead (a 2 m box lit by one face: 8 sweeps plain, 18 over-relaxed from
    // the third), and one sweep's ratio can be the correction's (a 1 m one: 0.10, then 1.10, then
    // 0.17). Should the change rise two sweeps running, plain again.
    bool relax = last && s_.gauss_seidel && !division_.divided && s_.relaxation != 1.0;
    int rises = 0, slow = 0;
    double before_change = 0;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      ++is.sweeps;
      const double omega = relax && slow >= 2 ? s_.relaxation : 1.0;
      // Importance steers the refinement, and the last round's sweeps past a round's own refine nothing
      // more: it is swept as in any round (the estimate reads it as they leave it).
      is.change = sweeps_.sweep(is, sweep < s_.sweeps, omega);
      // The correction walks every link, as a sweep does. Once the overall level is right (|c| under
      // kIdleCorrection) what is left are local modes it cannot touch: it skips 1, 2, 4, then 8 sweeps
      // between tries until it moves the level again, and always runs before the sweeps stop.
      if (correct && (wait == 0 || is.change <= s_.tolerance)) {
        double level = 0;
        is.change = std::max(is.change, aggregation_correction(h_, sweeps_.change_floor(), &level, &buffers));
        ++stats_.corrections;
        interval = level < kIdleCorrection ? std::min(std::max(2 * interval, 1), kMaxCorrectionInterval) : 0;
        wait = interval;
      } else if (correct) {
        --wait;
      }
      if (is.change <= s_.tolerance) break;
      if (slow < 2) slow = sweep >= s_.sweeps && is.change >= kSlowSweep * before_change ? slow + 1 : 0;
      rises = omega != 1.0 && is.change > before_change ? rises + 1 : 0;
      if (rises == 2) relax = false;
      before_change = is.change;
    }
    converged_before = is.change <= s_.tolerance;
    is.sweep_bytes = ranks_bytes_exchanged() - sweeps_from;
    estimate_round(is, it);
    const bool done = last && !settled && converged_before;
    if (done) stats_.converged = true;
    is.links = stats_.links;
    if (!done && !last && !state.stalled && refinement_stalled(stats_.iterations, is)) {
      state.stalled = true;  // the next round refines nothing: it converges these links
      stats_.stalled_round = it;
    }
    record(is, progress);
    save_round(state, it, done);
    if (done) break;
  }
  // The error each node's own links leave in its radiosity (HNode::error) and the statistics: the last
  // round's estimate measured them from this same state.
  stats_.above_tolerance +=
      last_round >= 0 && estimated_round_ == last_round
          ? estimated_above_
          : oracle_.measure_left_error([&](uint32_t i) { return here(i); }, [&](uint32_t i) { return refinement_.splittable(i); });
  stats_.white = oracle_.state().white;
  rank_work().links_held = 0;
  for (uint32_t i = 0; i < h_.nodes().size(); ++i)
    if (here(i)) rank_work().links_held += h_[i].links.size();
}

void Solver::estimate_round(IterationStats& is, int round) {
  if (!s_.estimate || stats_.links < s_.estimate_from_links) return;
  // Its scales and variation are those the next round's refinement reads (run() does not measure them again).
  estimated_above_ =
      oracle_.measure_left_error([&](uint32_t i) { return here(i); }, [&](uint32_t i) { return refinement_.splittable(i); });
  is.estimated_error = s_.estimate();
  estimated_round_ = round;
}

void Solver::save_round(RoundState& state, int round, bool finished) {
  state.next_round = round + 1;
  state.finished = finished;
  if (s_.save_round) s_.save_round(state.next_round, [&](ByteWriter& out) { save_state(out, state); });
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
  const uint64_t exchanged = ranks_bytes_exchanged();
  is.bytes_exchanged = exchanged - exchanged_before_;
  exchanged_before_ = exchanged;
  if (is.emitted == Vec3{} && !stats_.iterations.empty()) {  // no solve this round: keep the last
    is.emitted = stats_.iterations.back().emitted;
    is.absorbed = stats_.iterations.back().absorbed;
    is.residual = stats_.iterations.back().residual;
  }
  // Checked builds (walkrad/core/invariant.h): the tree, the links and B as a round leaves them. Not
  // energy: rows scaled to 1 in a closed scene without the closure balance may absorb more than is
  // emitted (office-floor's 2 rooms: 1.055; the energy audit reports it).
  WALKRAD_CHECK_FAULT(hierarchy_fault(h_));
  stats_.iterations.push_back(is);
  if (progress) progress(is);
}

}  // namespace hierarchical_detail

bool refinement_stalled(const std::vector<IterationStats>& rounds, const IterationStats& now) {
  if (rounds.size() < 2) return false;
  const IterationStats& before = rounds[rounds.size() - 2];
  if (now.estimated_error < 0 || before.estimated_error < 0) return false;
  // A rise is the round's sweeps not yet settled (office1's third round read 990% between 8.2% and 3.8%),
  // not the end of what links buy.
  return double(now.links) >= kStallGrowth * double(before.links) && now.estimated_error <= before.estimated_error &&
         now.estimated_error > (1 - kStallGain) * before.estimated_error;
}

const char* indivisible_because(const HierarchicalSettings& s) {
  // Gauss-Seidel's order runs through every polygon in turn; the closure balance's column sums and a
  // transmitting leaf's twin read links of other polygons.
  if (s.gauss_seidel) return "Gauss-Seidel sweeps: --solver jacobi divides them";
  if (s.closed) return "the closure balance (--effect closure=on) reads them across ranks";
  if (s.twins) return "transmission reads them across ranks";
  return nullptr;
}

const char* undivided_because(const HierarchicalSettings& s) {
  if (const char* why = indivisible_because(s)) return why;
  return s.save_round || s.resume ? "--checkpoint saves them in one file" : nullptr;
}

namespace {

// The weighted median of the polygons' squarest parts (a part no more elongated than 4 to 1: 4 × the
// short side squared, as split_element splits them), each weighed by weight(node); 0 without any.
template <class Weight>
double median_part(const Hierarchy& h, Weight weight) {
  std::vector<std::pair<double, double>> sizes;
  double total = 0;
  for (const HNode& n : h.nodes())
    if (!n.cluster && n.depth == 0 && n.area > 0 && weight(n) > 0) {
      double longest = 0;
      for (int k = 0; k < n.shape.count; ++k) longest = std::max(longest, length(n.shape.v[size_t((k + 1) % n.shape.count)] - n.shape.v[size_t(k)]));
      const double shortest = longest > 0 ? n.area / longest : 0.0;
      sizes.push_back({std::min(n.area, 4 * shortest * shortest), weight(n)});
      total += weight(n);
    }
  if (sizes.empty()) return 0;
  std::sort(sizes.begin(), sizes.end());
  double below = 0;
  for (const auto& [a, w] : sizes) {
    below += w;
    if (below >= 0.5 * total) return a;
  }
  return sizes.back().first;
}

}  // namespace

double default_min_area(const Hierarchy& h) {
  // A 128th of the median input polygon's side: the median taken by area (the size of the surfaces most
  // of the scene is made of), and with viewpoints the smaller of that and the median taken by what they
  // see of each polygon (its direct importance R). It scales with the scene's units; the same for a room
  // whatever the building around it. By area alone, a 24 m ground around a daylit room set it 70 times
  // what the room gives, and the room stayed coarse at every --error (5.1% against the reference at
  // 0.05, 1.3% so); by what is seen alone, the Cornell box's back wall set it 2.8 times larger and the
  // floor before the short block lost its contact shadow (14% against the reference). A polygon counts
  // as its squarest part: a corridor's floor one quad along the whole level would make the median, and
  // every tolerance, grow with the corridor's length.
  const double by_area = median_part(h, [](const HNode& n) { return n.area; });
  const double by_view = median_part(h, [](const HNode& n) { return n.R; });
  return (by_view > 0 ? std::min(by_area, by_view) : by_area) / (128.0 * 128.0);
}

void solve_hierarchical(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& settings, HierarchicalStats& stats,
                        const std::function<void(const IterationStats&)>& progress) {
  stats = {};
  if (h.nodes().empty()) return;
  hierarchical_detail::Solver solver(h, rays, settings, stats);
  solver.run(progress);
}

}  // namespace walkrad
