// The refinement, a part of the hierarchical solver (solver.h): which nodes are linked, at which level
// and with how many rays (Hanrahan, Salzman & Aupperle 1991; clusters: Smits, Arvo & Greenberg 1994),
// decided by the error oracle. It splits nodes and emits the round's new links as requests, plain data
// the link evaluator takes (link_evaluator.h); it never evaluates a link nor moves light. Defined in
// link_refinement.cpp (the rounds' passes, the punctual lights' splits), pair_refinement.cpp (pairs of
// nodes, breadth first) and divided_refinement.cpp (the receivers' plans exchanged among ranks).
// Private to this stage.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/visibility/shaft.h"
#include "division.h"
#include "error_oracle.h"
#include "link_evaluator.h"

namespace walkrad::hierarchical_detail {

// A refinement plan as the rank holding the receiver's links sends it to the others (a divided solve,
// divided_refinement.cpp): whether the receiver splits, and every link it does not keep (all of them
// when it splits), in the links' order.
struct RemoteLink {
  uint32_t index, source;
  uint16_t samples;
  uint8_t rays;
  uint8_t action;  // Refinement::LinkAction
};
struct RemotePlan {
  bool split_receiver = false;
  std::vector<RemoteLink> links;
};

class Refinement {
 public:
  // Marks the two-sided clusters, and with punctual lights gives every input polygon its direct
  // irradiance (refine_for_lights splits them once a solve has given the tolerances). The hierarchy, the
  // scene's rays, the settings, the statistics and the oracle must outlive the refinement.
  // typical_area: default_min_area, unless the settings give one.
  Refinement(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& s, HierarchicalStats& stats,
             const ErrorOracle& oracle, Division division, double typical_area);

  // The first refinement: pairs refined from (root, root), as high as links may go.
  void refine_first();
  // Elements split where the punctual lights' irradiance varies more than ε allows, level by level
  // (the irradiance of each level's new elements computed in parallel; the splits in a fixed order).
  void refine_for_lights();
  // Later rounds: receivers whose variation exceeds their tolerance get their links at their
  // children; links whose source or noise error exceeds a share of it get an end split. The oracle's
  // scales and variation are measured before.
  void refine_existing();
  // The direct irradiance of the elements the refinement created (punctual lights).
  void compute_missing_direct();

  // The round's new links, in the order the refinement asked for them: where this rank keeps their
  // receivers' links (all of them, unless divided), and how many there are on all ranks.
  std::vector<LinkRequest> take_requests();
  uint64_t new_link_count() const { return requests_.size() + elsewhere_; }
  uint64_t request_bytes() const { return requests_.capacity() * sizeof(LinkRequest); }

  bool splittable(uint32_t i) const;
  // The leaves under a close pair left whole (their own links or an ancestor's): a closed scene's row
  // scaling is not applied to them (normalise_closed_rows).
  std::vector<uint8_t> under_close_pairs() const;
  // A solve resumed past its first rounds: the punctual lights' splits are made.
  void forget_light_frontier();

  // How many times the rays a wholly hidden link is cast again with before it counts as unresolved.
  static constexpr int kHiddenRecast = 8;
  // A link's rays double past this many candidate blockers in its shaft, and double again past kMany.
  static constexpr size_t kSomeBlockers = 4, kManyBlockers = 64;

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
  // Decides a pair without changing anything (thread-safe; t.own is taken).
  PairOutcome decide_pair(PairTask& t) const;

  // What refine_existing does with one receiver's links (plan_receiver, from the state before the
  // pass): split the receiver (every link goes down to its children), or per link keep it, cast it
  // again with more rays, or refine it; with the candidate lists of the links to be split.
  enum LinkAction : uint8_t { kKeep, kRecast, kSplit };
  struct ReceiverPlan {
    bool split_receiver = false;
    std::vector<LinkAction> action;                 // by link, unless the receiver splits
    std::vector<std::vector<uint32_t>> candidates;  // by link, where one is split: link_candidates
  };
  // with_candidates false: the actions alone (a divided solve sends them, divided_refinement.cpp).
  ReceiverPlan plan_receiver(uint32_t i, bool with_candidates = true) const;

 private:
  // A link whose every ray was blocked but whose occlusion is not proven (a link proven hidden is
  // dropped: evaluate): 0, with what its rays could have missed as σ. A few rays miss a doorway seen
  // from the far end of a long corridor floor, so its light may still pass.
  static bool hidden(const Link& l) { return l.F == 0 && l.sigma > 0; }
  // Hidden, not yet cast again with kHiddenRecast times the rays.
  bool recastable(const Link& l) const { return hidden(l) && l.samples > 0 && int(l.samples) < kHiddenRecast * s_.rays; }
  // Cast again and every ray still blocked, yet not proven: what passes is below 3/n of its unoccluded
  // form factor with 95% confidence (ErrorOracle::kHiddenBound σ), so it is refined (receiver or source)
  // while that much would matter (worth_splitting), and kept at 0 with its σ in the estimate once it
  // would not. Its children's links are proven hidden, see the part of the source that passes, or are
  // left smaller and unresolved.
  bool unresolved(const Link& l) const { return hidden(l) && !recastable(l); }

  Vec3 transmittance(const HNode& n) const { return simulated_transmittance(h_, s_, n); }
  const std::vector<PunctualLight>* lights() const { return simulated_lights(s_); }
  bool here(uint32_t i) const { return division_.here(h_, i); }

  // Clusters that hold a transmitting polygon or its twin (transmission.h). A cluster link sends the
  // area mean of its surfaces' radiosity and pushes what it receives evenly onto them, but the two
  // sides of a lampshade see different worlds: the bright inside, hidden from the room, and the room.
  // With the twins in a cluster, the lit outside of a shade would gather a row sum of 0.24, and a closed
  // room would lose light (the transmission test's room absorbs 0.9958 of the emitted power that way,
  // 1.000000 with these clusters marked; see docs/numerics.md). Links never end at such a cluster: they
  // go down to the transmitting polygons' own elements (a lampshade's few polygons; many transmitting
  // polygons make many links).
  void mark_two_sided_clusters();
  bool two_sided(uint32_t i) const { return i < two_sided_.size() && two_sided_[i]; }

  // Direct irradiance of the given elements (4 × 4 points each, a shadow ray per point and light), in
  // parallel; returns how unevenly each one shows it (ρ × the spread, plus τ × the back's).
  std::vector<double> direct_for(const std::vector<uint32_t>& elements);
  // The spots (light_spots) those samples missed: each node's spread widened by what up to
  // kSpotsPerNode spots inside it show against its mean, at a shadow-ray evaluation each; the spots in
  // none of the nodes (settled elsewhere) are dropped.
  static constexpr int kSpotsPerNode = 4;
  void widen_by_spots(const std::vector<uint32_t>& elements, std::vector<double>& spread);

  // Whether the receiver's display needs a close pair (close_pair) split: an error as large as what it
  // shows stays within its tolerance where its display weight is under e.
  bool close_matters(uint32_t i) const { return !oracle_.importance() || oracle_.display_weight(i) >= s_.error; }

  // s_.rays rays between random points of i and j that face each other (a stream of its own, not the
  // link's), into out's probe_rays and probe_hidden.
  void probe(uint32_t i, uint32_t j, PairOutcome& out) const;
  // Refines pairs level by level (breadth first): each level's decisions, whose shaft tests are most of
  // the refinement's time, in parallel; then, in the level's order, its links appended to the round's
  // list and its splits made (nodes numbered in that order), their children's pairs forming the next
  // level. A decision reads only nodes as the splits leave them (a child starts from its parent's
  // values), not what other pairs decided, so nodes and links come out the same whatever the thread
  // count.
  void refine_pairs(std::vector<PairTask> tasks);

  // The polygons that can block between nodes i and j (shaft.h); with volumetric visibility, volume
  // clusters the multi-resolution rule accepts for this link stand whole (tagged). A shaft where the
  // rule accepts some volumes but another volume's polygons must block exactly is evaluated exactly
  // throughout: the grid holds every volume, the solid scene none. Without volumes the lists are
  // compact (shaft.h: a tree node wholly inside the shaft is one entry).
  bool compact() const { return !s_.volumes || !s_.visibility; }
  std::vector<uint32_t> occluders(uint32_t i, uint32_t j, const Shaft& shaft, uint32_t ex_i, uint32_t ex_j,
                                  const std::vector<uint32_t>* parent) const;

  // Appends a new link to the round's list where this rank keeps its receiver's links; counts it
  // either way (the round's new links are the same count on every rank).
  void add_pending(const LinkRequest& r) {
    if (here(r.receiver)) requests_.push_back(r);
    else ++elsewhere_;
  }

  // Every element receiver's plan with something to do, from the rank that holds its links, to every
  // rank: plan_of[i] indexes plans (UINT32_MAX: keep every link).
  void exchange_plans(std::vector<uint32_t>& plan_of, std::vector<RemotePlan>& plans) const;
  // The candidate lists the plan's split links need (link_candidates), computed on every rank.
  std::vector<std::vector<uint32_t>> remote_candidates(uint32_t i, const RemotePlan& plan) const;
  // What refine_existing does with element receiver i's plan: on every rank the same splits and new
  // links; where its links are held, the kept ones stay (candidates: taken, as refine takes its own).
  void apply_plan(uint32_t i, const RemotePlan& plan, std::vector<std::vector<uint32_t>>& candidates);

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

  Hierarchy& h_;
  const RayScene& rays_;
  const HierarchicalSettings& s_;
  HierarchicalStats& stats_;
  const ErrorOracle& oracle_;
  const Division division_;
  double min_area_ = 0;
  std::vector<uint8_t> two_sided_;        // by node: a cluster holding a transmitting polygon or a twin
  std::vector<uint32_t> light_frontier_;  // the input polygons' elements and their punctual-light spread,
  std::vector<double> light_spread_;      // from the constructor to refine_for_lights
  std::vector<LightSpot> light_spots_;    // where directional lights reach, inside the light frontier
  double spot_shown_ = 0;                 // the most a spot shows (ρ E): the scale where nothing else is lit
  std::vector<LinkRequest> requests_;     // the round's new links, as the refinement asks for them
  uint64_t elsewhere_ = 0;                // this round's new links whose receivers another rank holds
  // The pairs refine_existing's receivers hand on (replace_link, split_link), refined a batch at a time,
  // and the lists they filter (a deque: a list stays where it is while others are added).
  std::vector<PairTask> queued_pairs_;
  std::deque<std::vector<uint32_t>> queued_lists_;
  static thread_local std::vector<uint8_t> blocked_scratch_;
  static thread_local std::vector<RayScene::Segment> probe_scratch_;
};

}  // namespace walkrad::hierarchical_detail
