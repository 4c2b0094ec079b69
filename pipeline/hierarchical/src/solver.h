// The hierarchical solver's state and steps (hierarchical_solver.h), private to this stage. It holds three
// parts of its own, each a class with its header: the link evaluator (link_evaluator.h: pending links
// in, evaluated links out), the error oracle (error_oracle.h: tolerances, and the error links leave) and
// the sweeps (sweeps.h: gather, push-pull, importance). Its own methods in a file per step: the rounds
// (hierarchical_solver.cpp), the refinement of links (link_refinement.cpp, pair_refinement.cpp), the
// round's links around their evaluation (round_links.cpp), those steps as a solve whose links are divided among ranks runs them (divided_solve.cpp), and its
// state between rounds (solve_checkpoint.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <utility>
#include <vector>

#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/hierarchical/directional_irradiance.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/link_owners.h"
#include "walkrad/hierarchical/transmission.h"
#include "error_oracle.h"
#include "link_evaluator.h"
#include "sweeps.h"
#include "walkrad/core/huge_pages.h"
#include "walkrad/core/sampling.h"
#include "walkrad/visibility/shaft.h"

namespace walkrad::hierarchical_detail {

// A refinement plan as the rank holding the receiver's links sends it to the others (a divided solve,
// divided_solve.cpp): whether the receiver splits, and every link it does not keep (all of them when it
// splits), in the links' order.
struct RemoteLink {
  uint32_t index, source;
  uint16_t samples;
  uint8_t rays;
  uint8_t action;  // Solver::LinkAction
};
struct RemotePlan {
  bool split_receiver = false;
  std::vector<RemoteLink> links;
};

class Solver {
 public:
  Solver(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& s, HierarchicalStats& stats);

  // Elements split where the punctual lights' irradiance varies more than ε allows, level by level
  // (the irradiance of each level's new elements computed in parallel; the splits in a fixed order).
  void refine_for_lights();

  // Clusters that hold a transmitting polygon or its twin (transmission.h). A cluster link sends the
  // area mean of its surfaces' radiosity and pushes what it receives evenly onto them, but the two
  // sides of a lampshade see different worlds: the bright inside, hidden from the room, and the room.
  // With the twins in a cluster, the lit outside of a shade would gather a row sum of 0.24, and a closed
  // room would lose light (the transmission test's room absorbs 0.9958 of the emitted power that way,
  // 1.000000 with these clusters marked; the lamp room, whose leak lies elsewhere, absorbs 0.9965
  // without this and 0.9957 with it: see docs/numerics.md). Links never end at such a cluster: they go down to the transmitting polygons'
  // own elements (a lampshade's few polygons; many transmitting polygons make many links).
  void mark_two_sided_clusters();
  bool two_sided(uint32_t i) const { return i < two_sided_.size() && two_sided_[i]; }

  // Rounds of refine → evaluate → solve. A round that adds no link solves to convergence; the
  // search stops only when a refinement pass over the converged solution adds none either (links
  // kept while B was still growing are checked again against the final B).
  void run(const std::function<void(const IterationStats&)>& progress);

  // A closed scene: every leaf receives a row sum of 1 and sends all of its power (link_transport.h).
  void balance_closed();

  void record(IterationStats& is, const std::function<void(const IterationStats&)>& progress);

  // Where run() stands between rounds, saved with the rest of the state (solve_checkpoint.cpp).
  struct RoundState {
    int next_round = 0;
    bool converged_before = false;
    bool finished = false;  // converged: what follows the rounds is all that is left
  };
  void save_round(RoundState& state, int round, bool finished);
  void save_state(ByteWriter& out, const RoundState& round) const;
  RoundState load_state(ByteReader& in);  // throws ByteFormatError for bytes that do not fit

 private:
  // How many times the rays a wholly hidden link is cast again with before it counts as unresolved.
  static constexpr int kHiddenRecast = 8;
  // A link whose every ray was blocked but whose occlusion is not proven (a link proven hidden is
  // dropped: evaluate): 0, with what its rays could have missed as σ. A few rays miss a doorway seen
  // from the far end of a long corridor floor, so its light may still pass.
  static bool hidden(const Link& l) { return l.F == 0 && l.sigma > 0; }
  // Hidden, not yet cast again with kHiddenRecast times the rays.
  bool recastable(const Link& l) const { return hidden(l) && l.samples > 0 && int(l.samples) < kHiddenRecast * s_.rays; }
  // Cast again and every ray still blocked, yet not proven: what passes is below 3/n of its unoccluded
  // form factor with 95% confidence (ErrorOracle::kHiddenBound σ), so it is refined (receiver or source) while that
  // much would matter (worth_splitting), and kept at 0 with its σ in the estimate once it would not.
  // Its children's links are proven hidden, see the part of the source that passes, or are left
  // smaller and unresolved.
  bool unresolved(const Link& l) const { return hidden(l) && !recastable(l); }
  // A link's rays double past this many candidate blockers in its shaft, and double again past kMany.
  static constexpr size_t kSomeBlockers = 4, kManyBlockers = 64;
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

  Vec3 transmittance(const HNode& n) const { return simulated_transmittance(h_, s_, n); }
  bool luminaire(const HNode& s) const { return walkrad::hierarchical_detail::luminaire(h_, s_, s); }
  const std::vector<PunctualLight>* lights() const { return simulated_lights(s_); }

  // Direct irradiance of the given elements (4 × 4 points each, a shadow ray per point and light), in
  // parallel; returns how unevenly each one shows it (ρ × the spread, plus τ × the back's).
  std::vector<double> direct_for(const std::vector<uint32_t>& elements);

  void compute_missing_direct();

  bool splittable(uint32_t i) const;

  // Whether the receiver's display needs a close pair (close_pair) split: an error as large as what it
  // shows stays within its tolerance where its display weight is under e.
  bool close_matters(uint32_t i) const { return !oracle_.importance() || oracle_.display_weight(i) >= s_.error; }
  // The leaves under a close pair left whole (their own links or an ancestor's): a closed scene's row
  // scaling is not applied to them (normalise_closed_rows).
  std::vector<uint8_t> under_close_pairs() const;

  // The first refinement: refine_pairs from (root, root), as high as links may go.
  void refine_first();

  // A pair of nodes to refine (refine_pairs): receiver i, source j; the candidate occluders its shaft
  // filters (parent: its parent pair's list; none: its own, or searched from the tree); force: split it
  // whatever the tests say (refine_existing decided it with the link's own form factor, which a new
  // pair does not have yet).
  struct PairTask {
    uint32_t i, j;
    const std::vector<uint32_t>* parent;
    bool force;
    bool has_own = false;
    std::vector<uint32_t> own;
    PairTask(uint32_t i_, uint32_t j_, const std::vector<uint32_t>* parent_ = nullptr, bool force_ = false)
        : i(i_), j(j_), parent(parent_), force(force_) {}
  };
  // What the refinement decides for one pair from the hierarchy as it stands: drop it (coplanar or
  // facing away), open a cluster's self-pair into its children's pairs, link it with so many rays, or
  // split one end (the receiver or the source) and refine the children's pairs with its list.
  enum class PairKind : uint8_t { kDrop, kSelf, kLink, kSplitEnd };
  struct PairOutcome {
    PairKind kind = PairKind::kDrop;
    bool split_receiver = false, need_rays = false, volume = false;
    int32_t samples = 0;
    std::vector<uint32_t> candidates;  // kSplitEnd: the pair's list, which its children's shafts filter
    uint32_t probe_rays = 0;           // cast by probe (0: not probed, or nothing faced)
    bool probe_hidden = false;         // every probe ray blocked
  };
  // s_.rays rays between random points of i and j that face each other (a stream of its own, not the
  // link's), into out's probe_rays and probe_hidden.
  void probe(uint32_t i, uint32_t j, PairOutcome& out) const;
  // Decides a pair without changing anything (thread-safe; t.own is taken).
  PairOutcome decide_pair(PairTask& t) const;
  // Refines pairs level by level (Hanrahan, Salzman & Aupperle 1991, breadth first): each level's
  // decisions, whose shaft tests are most of the refinement's time, in parallel; then, in the level's
  // order, its links appended to the round's list and its splits made (nodes numbered in that order),
  // their children's pairs forming the next level. A decision reads only nodes as the splits leave
  // them (a child starts from its parent's values), not what other pairs decided, so nodes and links
  // come out the same whatever the thread count.
  void refine_pairs(std::vector<PairTask> tasks);

  // The polygons that can block between nodes i and j (shaft.h); with volumetric visibility, volume
  // clusters the multi-resolution rule accepts for this link stand whole (tagged). A shaft where the
  // rule accepts some volumes but another volume's polygons must block exactly is evaluated exactly
  // throughout: the grid holds every volume, the solid scene none. Without volumes the lists are
  // compact (shaft.h: a tree node wholly inside the shaft is one entry).
  bool compact() const { return !s_.volumes || !s_.visibility; }
  std::vector<uint32_t> occluders(uint32_t i, uint32_t j, const Shaft& shaft, uint32_t ex_i, uint32_t ex_j,
                                  const std::vector<uint32_t>* parent) const;

  // Later rounds: receivers whose variation exceeds their tolerance get their links at their
  // children; links whose source or noise error exceeds a share of it get an end split.
  void refine_existing();

  // What refine_existing does with one receiver's links (plan_receiver, from the state before the
  // pass): split the receiver (every link goes down to its children), or per link keep it, cast it
  // again with more rays, or refine it; with the candidate lists of the links to be split.
  enum LinkAction : uint8_t { kKeep, kRecast, kSplit };
  struct ReceiverPlan {
    bool split_receiver = false;
    std::vector<LinkAction> action;                 // by link, unless the receiver splits
    std::vector<std::vector<uint32_t>> candidates;  // by link, where one is split: link_candidates
  };
  // with_candidates false: the actions alone (a divided solve sends them, divided_solve.cpp).
  ReceiverPlan plan_receiver(uint32_t i, bool with_candidates = true) const;

  // --- divided_solve.cpp: the links divided among ranks (link_owners.h) ---

  // Whether this rank keeps the links of receiver i (always, unless the solve is divided).
  bool here(uint32_t i) const { return !divided_ || holds_links(h_, i); }
  // Appends a new link to the round's list where this rank keeps its receiver's links; counts it
  // either way (the round's new links are the same count on every rank).
  void add_pending(const LinkRequest& r) {
    if (here(r.receiver)) requests_.push_back(r);
    else ++elsewhere_;
  }
  uint64_t new_link_count() const { return requests_.size() + elsewhere_; }  // between refinement and evaluation
  // The round's requests made into pending_ (at its exact size), the requests given back.
  void take_requests();

  // Every element receiver's plan with something to do, from the rank that holds its links, to every
  // rank: plan_of[i] indexes plans (UINT32_MAX: keep every link).
  void exchange_plans(std::vector<uint32_t>& plan_of, std::vector<RemotePlan>& plans) const;
  // The candidate lists the plan's split links need (link_candidates), computed on every rank.
  std::vector<std::vector<uint32_t>> remote_candidates(uint32_t i, const RemotePlan& plan) const;
  // What refine_existing does with element receiver i's plan: on every rank the same splits and new
  // links; where its links are held, the kept ones stay.
  // (candidates: taken, as refine takes its own list.)
  void apply_plan(uint32_t i, const RemotePlan& plan, std::vector<std::vector<uint32_t>>& candidates);
  // evaluate_pending, divided: this rank's receivers' links here, the clusters' by blocks shared.
  void evaluate_divided(IterationStats& is);
  // The gather's results (H, Fsum, and the shares Hp, Fp its parent pushed) of every element node,
  // from the rank that gathered it.
  void share_gathered();
  // Importance shot along the links in 2^-k units of its total: integer sums, the same in any order,
  // whatever rank adds which link (Jacobi sweeps).
  void shoot_importance_exactly();
  // The most bytes this rank's links and new-link list hold now, kept as the peak (stats, ranks.h).
  void note_link_memory();

  // Replaces link l (to receiver i) by the same link cast with kHiddenRecast times its rays.
  void recast(uint32_t i, const Link& l);
  // Replaces link l (to receiver i) by finer links: from the receiver's children where the receiver
  // splits (split_link), else from whichever end the refinement splits; candidates: the pair's (taken).
  // The pairs are queued (queued_pairs_) and refined with the batch's others.
  void replace_link(uint32_t i, const Link& l, bool split_receiver, std::vector<uint32_t>& candidates);
  // Replaces link l (to receiver i) by pairs from the receiver's children, split now; candidates: the
  // pair's (taken).
  void split_link(uint32_t i, const Link& l, std::vector<uint32_t>& candidates);
  // An existing link that needed no rays had no candidate occluder, nor have its children, whose
  // shafts lie inside its own.
  bool ray_free(const Link& l) const;
  // The candidate occluders of an existing link's shaft (none where it is ray-free).
  std::vector<uint32_t> link_candidates(uint32_t i, const Link& l) const;

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




  Hierarchy& h_;
  const RayScene& rays_;
  const HierarchicalSettings& s_;
  HierarchicalStats& stats_;
  const LinkEvaluator evaluator_;  // the links' form factors (link_evaluator.h)
  const double typical_area_;      // default_min_area: a 128th of the median polygon's side, squared
  ErrorOracle oracle_;             // tolerances and the error links leave (error_oracle.h)
  double min_area_ = 0;
  uint64_t exchanged_before_ = 0;  // ranks_bytes_exchanged() when the last round was recorded
  std::vector<uint32_t> light_frontier_;  // the input polygons' elements and their punctual-light spread,
  std::vector<double> light_spread_;      // from the constructor to refine_for_lights
  std::vector<LinkRequest> requests_;  // the round's new links, as the refinement asks for them
  PendingList pending_;                // the same, to evaluate (take_requests)
  // The pairs refine_existing's receivers hand on (replace_link, split_link), refined a batch at a time,
  // and the lists they filter (a deque: a list stays where it is while others are added).
  std::vector<PairTask> queued_pairs_;
  std::deque<std::vector<uint32_t>> queued_lists_;
  // Jacobi sweeps, no closure balance, no transmission: the steps that read links run as a divided
  // solve runs them, whatever the rank count, so that its result is the same (link_owners.h).
  const bool divisible_;
  const bool divided_;   // divisible, over several ranks, no checkpoints: links divided among ranks
  uint64_t elsewhere_ = 0; // this round's new links whose receivers another rank holds
  std::vector<uint8_t> two_sided_;  // by node: a cluster holding a transmitting polygon or a twin
  static thread_local std::vector<uint8_t> blocked_scratch_;
  static thread_local std::vector<RayScene::Segment> probe_scratch_;
  Sweeps sweeps_;  // the transport (sweeps.h): made last, it reads the division above
};

}  // namespace walkrad::hierarchical_detail
