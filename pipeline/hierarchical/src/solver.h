// The hierarchical solver (hierarchical_solver.h), private to this stage: the rounds of refine →
// evaluate → solve, over four parts with plain data between them, each a class with its header: the
// refinement (refinement.h: nodes split, the round's new links emitted as requests), the link evaluator
// (link_evaluator.h: pending links in, evaluated links out), the error oracle (error_oracle.h:
// tolerances, and the error links leave) and the sweeps (sweeps.h: gather, push-pull, importance). How
// the solve is divided among ranks is one value handed to each (division.h). The solver's own steps:
// the rounds (hierarchical_solver.cpp), the round's links around their evaluation (round_links.cpp) and
// its state between rounds (solve_checkpoint.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "division.h"
#include "error_oracle.h"
#include "link_evaluator.h"
#include "refinement.h"
#include "sweeps.h"

namespace walkrad::hierarchical_detail {

class Solver {
 public:
  Solver(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& s, HierarchicalStats& stats);

  // Rounds of refine → evaluate → solve. A round that adds no link solves to convergence; the
  // search stops only when a refinement pass over the converged solution adds none either (links
  // kept while B was still growing are checked again against the final B).
  void run(const std::function<void(const IterationStats&)>& progress);

  // A closed scene: every leaf receives a row sum of 1 and sends all of its power (link_transport.h).
  void balance_closed();

  void record(IterationStats& is, const std::function<void(const IterationStats&)>& progress);
  // The error the round leaves, as the bake estimates it (HierarchicalSettings::estimate), into is, once
  // the solve holds HierarchicalSettings::estimate_from_links links.
  void estimate_round(IterationStats& is, int round);

  // Where run() stands between rounds, saved with the rest of the state (solve_checkpoint.cpp).
  struct RoundState {
    int next_round = 0;
    bool converged_before = false;
    bool finished = false;  // converged: what follows the rounds is all that is left
    bool stalled = false;   // refinement_stalled: the rounds left only converge the links there are
  };
  void save_round(RoundState& state, int round, bool finished);
  void save_state(ByteWriter& out, const RoundState& round) const;
  RoundState load_state(ByteReader& in);  // throws ByteFormatError for bytes that do not fit

 private:
  // Refinement stops after a round that adds fewer than 1 / kLastRoundShare of the links.
  static constexpr size_t kLastRoundShare = 20;
  // An aggregation correction that scales the reflected light by less than this is idle (run()).
  static constexpr double kIdleCorrection = 1e-3;
  static constexpr int kMaxCorrectionInterval = 8;
  // The last round over-relaxes (HierarchicalSettings::relaxation) once two plain sweeps past its
  // first each left at least this share of the change before it: slow local modes (office-floor 0.40
  // and 0.56 at 8 rooms, 0.59 and 0.58 at 32 rooms), not fast ones (a 1 m box lit by one face:
  // 0.10–0.24 but once).
  static constexpr double kSlowSweep = 0.3;

  const std::vector<PunctualLight>* lights() const { return simulated_lights(s_); }
  bool here(uint32_t i) const { return division_.here(h_, i); }

  // --- round_links.cpp ---

  // The refinement's requests made into pending_ (at its exact size).
  void take_requests();
  // Form factors of the new links, in parallel: each link draws from its own random stream.
  void evaluate_pending(IterationStats& is);
  // A wholly hidden link stays while it may still see something.
  static bool kept(const Pending& p) { return p.F > 0 || p.sigma > 0; }
  // What a list of evaluated links adds to the statistics, as integers (a divided solve sums each
  // rank's: any order), and the statistics so added.
  enum LinkCount { kRays, kVolume, kGridSegments, kExact, kUnoccluded, kMonteCarlo, kKept, kProven, kLinkCounts };
  using LinkCounts = std::array<int64_t, kLinkCounts>;
  LinkCounts count_links(const PendingList& list) const;
  void add_counts(const LinkCounts& counts, IterationStats& is);
  // The kept links of an evaluated list put at their receivers, each receiver's list grown once.
  void store_links(PendingList& list);
  // evaluate_pending, divided: this rank's receivers' links here, the clusters' by blocks shared.
  void evaluate_divided(IterationStats& is);
  // The most bytes this rank's links and new-link lists hold now (with the requests taken from the
  // refinement and not yet freed), kept as the peak (stats, ranks.h).
  void note_link_memory(uint64_t taken_requests = 0);

  Hierarchy& h_;
  const RayScene& rays_;
  const HierarchicalSettings& s_;
  HierarchicalStats& stats_;
  const LinkEvaluator evaluator_;  // the links' form factors (link_evaluator.h)
  const double typical_area_;      // default_min_area: a 128th of the median polygon's side, squared
  ErrorOracle oracle_;             // tolerances and the error links leave (error_oracle.h)
  uint64_t exchanged_before_ = 0;  // ranks_bytes_exchanged() when the last round was recorded
  int estimated_round_ = -1;       // the last round estimate_round measured,
  uint64_t estimated_above_ = 0;   // and how many nodes it left above their tolerance
  const Division division_;        // how the solve is divided among ranks (division.h)
  Refinement refinement_;          // which nodes are linked (refinement.h)
  PendingList pending_;            // the round's new links, to evaluate (take_requests)
  Sweeps sweeps_;                  // the transport (sweeps.h)
};

}  // namespace walkrad::hierarchical_detail
