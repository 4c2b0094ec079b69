// The transport, a part of the hierarchical solver (solver.h): sweeps that gather along the links,
// push-pull radiosity down and up the hierarchy, and shoot and push-pull importance (Hanrahan, Salzman
// & Aupperle 1991; importance: Smits, Arvo & Salesin 1992). Defined in solve_sweep.cpp. It changes the
// nodes' radiosity and importance, never the links; how the solve is divided among ranks is handed in
// (division.h: divided_sweep.cpp does what a divided sweep adds). Private to this stage.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "division.h"
#include "error_oracle.h"
#include "walkrad/hierarchical/directional_irradiance.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad::hierarchical_detail {

// What the sweeps keep between rounds, saved with the solve's state.
struct SweepState {
  double change = 0;                          // the last sweep's largest weighed change
  std::vector<DirectionalIrradiance> cube;    // by cluster (HNode::tree_node): its own links' gather
};

class Sweeps {
 public:
  // The hierarchy, the settings and the oracle must outlive the sweeps.
  Sweeps(Hierarchy& h, const HierarchicalSettings& s, const ErrorOracle& oracle, Division division);

  // Changes are measured relative to the leaf's radiosity, but not below 1e-9 of the brightest
  // emitter's (its emission and its punctual lights' part, D: measured once D is known): a closed dark
  // room's last traces of light decay by ρ per sweep and would keep their relative change until they
  // underflow (3,853 sweeps in the junction scene).
  void measure_change_floor();

  // Gauss-Seidel gathers in blocks (made once a round, the links as they stay through its sweeps): runs
  // of the clusters and polygons that gather, in the walk's order, none of whose links reads what the
  // walk changes within the run. A block's nodes gather in parallel at its start; any thread count
  // gives the same bytes.
  void plan_gather_blocks();

  // One sweep: gather along the links, push-pull radiosity, shoot and push-pull importance (unless
  // with_importance is false). Jacobi gathers every node from the previous sweep's radiosity;
  // Gauss-Seidel gathers each input polygon's quadtree just before pushing it down, so it sees what
  // the polygons before it got this sweep, and each cluster as the walk reaches it. Returns the
  // largest relative change of a leaf's radiosity, weighed by its display weight.
  // ω: the over-relaxation of the leaves' gathered irradiance (1: a plain Gauss-Seidel or Jacobi sweep).
  double sweep(IterationStats& is, bool with_importance = true, double relaxation = 1.0);

  SweepState& state() { return state_; }
  const SweepState& state() const { return state_; }
  double change_floor() const { return change_floor_; }

 private:
  bool here(uint32_t i) const { return division_.here(h_, i); }
  // Divided (divided_sweep.cpp): every element node's gather (H, Fsum, and the shares Hp, Fp its parent
  // pushed) from the rank that gathered it.
  void share_gathered();
  // Divisible (divided_sweep.cpp): importance shot along the links in 2^-k units of its total, integer
  // sums, the same in any order whatever rank adds which link.
  void shoot_importance_exactly();

  // Pushes irradiance H and the row sum S (Σ F along the path) down. A leaf whose row sum is well
  // above 1 receives more than any enclosure could send it: coincident surfaces in the input (two
  // lamp shades in one place: S = 3.5 in the MGF hospital) create power there and make the iteration
  // diverge. Its irradiance is scaled back to a row sum of 1. Row sums slightly above 1 are left: near
  // corners pushed averages overstate some leaves and understate others (up to 1.24 in the furnace),
  // and clamping only one side would lose power.
  void gather(HNode& n);
  void gather_block(size_t b);

  // What link l of receiver n takes from its source this sweep: a cluster source's radiosity towards n
  // (its parts' where the link saw them unevenly: Link::seen), an element's Bt.
  Vec3 sent_to(const HNode& n, const Link& l) const;

  // down, down_sum: what the element ancestors' links push here; cube: what the cluster ancestors'
  // links hold by direction (taken by the first element below them).
  Vec3 push_pull(uint32_t i, const Vec3& down, double down_sum, const DirectionalIrradiance& cube, IterationStats& is);
  double push_pull_importance(uint32_t i, double down);

  Vec3 twin_irradiance(const HNode& n) const;
  // The importance of the twin's node at n's place, by n's share of its area (as last pushed).
  double twin_importance(const HNode& n) const;

  Hierarchy& h_;
  const HierarchicalSettings& s_;
  const ErrorOracle& oracle_;
  const Division division_;
  SweepState state_;
  double change_floor_ = 0;
  double relax_ = 1.0;  // ω of the sweep under way (sweep's argument, read by push_pull)
  std::vector<uint32_t> block_nodes_;  // every node that gathers, block by block
  // Block b's nodes: [block_start_[b], block_start_[b + 1]); the walk reaches the block at its first.
  std::vector<size_t> block_start_;
  size_t next_block_ = 0;
  // Each cluster's Bt by the way its surfaces face (cluster_radiosity.h), set at each sweep's start.
  std::vector<std::array<Vec3, 6>> facing_bt_;
  std::vector<double> shot_scratch_;  // by node: the importance a sweep shoots
};

}  // namespace walkrad::hierarchical_detail
