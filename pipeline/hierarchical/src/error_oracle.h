// The refinement's oracle, a part of the hierarchical solver (solver.h): what a node may err by (its
// tolerance, from the display's white and the walkthrough's importance), what its links leave in its
// radiosity (the variation over its children, the sources' means, the form factors' noise), and
// whether a pair of nodes carries too much to be left to its mean. It reads the hierarchy and keeps its
// measures in plain data (OracleState), which the solve saves with its state between rounds. The
// definitions, and the mathematics, in error_estimate.cpp. Private to this stage.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad::hierarchical_detail {

// The oracle's measures, by node (the nodes as they stood when measured; a node made since reads its
// ancestor's).
struct OracleState {
  double white = 0;             // the display's white (update_scales)
  bool direct_weights = false;  // display weights from the direct importance R (the first refinement)
  std::vector<float> variation;  // measure_variation: ρ_c |H_c − H| at the worst child (the refinement's test)
  std::vector<float> left;       // measure_variation: the RMS error that variation leaves inside the children
  std::vector<float> spread;     // the range of its leaves' sent radiosity (measure_spread)
  std::vector<float> emitted;    // the luminance of its leaves' emission as sent, area mean (measure_spread)
  std::vector<float> weight;     // its display weight (update_scales)
};

// What a node sends along its links (the gather's source term): its radiosity as links carry it, or
// its emission alone where indirect light is not simulated.
inline const Vec3& sent(const HierarchicalSettings& s, const HNode& n) { return s.indirect ? n.Bt : n.emission; }

class ErrorOracle {
 public:
  // The hierarchy and the settings must outlive the oracle; it writes only HNode::error
  // (measure_left_error). quantum_area: a texel of the scene's typical surface (worth_splitting).
  ErrorOracle(Hierarchy& h, const HierarchicalSettings& s, double quantum_area);

  // Display weights from the walkthrough's importance, in units of seen_density: the importance per unit
  // area of a surface the views barely see (kSeenQuantile of the seen area is seen less). Without this
  // call every node weighs 1.
  void weigh_by_importance(double seen_density);
  bool importance() const { return importance_; }
  static constexpr double kSeenQuantile = 0.1;

  OracleState& state() { return state_; }
  const OracleState& state() const { return state_; }

  // The white of the display (the 95th percentile of the leaves' luminance, by area times display
  // weight, mapped to 0.9 as the exposure does) and the display weights.
  void update_scales();

  // How much a node matters to the walkthrough, in [0, 1]: 1 without importance; with it, a leaf's
  // importance per unit area over seen_density: what the views see counts fully, what only lights it
  // by its share; a node above leaves, their largest.
  double display_weight(uint32_t i) const;

  // The error allowed in a node's radiosity (luminance, W/m²): the requested relative error of what
  // it shows, its radiosity between kDarkShare and 1 times the white, over its display weight.
  double tolerance(uint32_t i) const;

  // variation and left for every node with links, in parallel: how far its children's radiosity would
  // differ from one another if its links were gathered at the children (Link::share), and the RMS
  // error that leaves inside the children (the estimate's share of it, see measure_left_error); and
  // the spreads first (measure_spread).
  void measure_variation();

  // A link carries too much to be left to its mean (Hanrahan, Salzman & Aupperle's BF criterion, made
  // local): ρ_i B_j F̂_ij A_i × display weight above e × white × the quantum area. Never for a uniform
  // source in full view (occluded: something can block between them), whose transfer the contour
  // formula gives exactly, however much it carries: the receiver test splits it where it falls unevenly.
  // link: the pair's link where it has been evaluated (its form factor, or for a wholly hidden one the
  // part its rays could have missed, kHiddenBound σ, replaces the estimate).
  bool worth_splitting(uint32_t i, uint32_t j, bool occluded, const Link* link = nullptr) const;
  // A link whose every ray was blocked passes less than this many σ (3/n of its unoccluded form factor
  // for n rays) with 95% confidence: the "rule of three".
  static constexpr double kHiddenBound = 3.0;

  // update_scales, measure_variation, then each node's own error (HNode::error) where here(i) (the rank holding its links; the others' are shared);
  // splittable: whether a leaf source can still split (one that cannot has no finer parts to err by).
  // Returns how many nodes exceed their tolerance.
  uint64_t measure_left_error(const std::function<bool(uint32_t)>& here, const std::function<bool(uint32_t)>& splittable);

 private:
  // spread and emitted: the range of luminance a node's leaves send, for every node.
  void measure_spread();

  // The error in the receiver's radiosity from taking the source's mean radiosity: its children's
  // radiosity weighted by the kernel from the receiver against the mean (a leaf source: its own
  // variation, half of it, where it can split).
  double source_error(const HNode& ri, const Link& l, const std::function<bool(uint32_t)>& splittable) const;

  const Vec3& sent(const HNode& n) const { return hierarchical_detail::sent(s_, n); }
  // What a link takes from its source: sent, or the source's children's weighed by Link::seen.
  Vec3 link_sent(const Link& l) const;

  // Whether node i's radiosity reaches the display through the final gather (HierarchicalSettings::
  // gathered): its direct light from area emitters is evaluated at the vertices, not taken from links.
  bool gathered(uint32_t i) const;
  // The luminance of what a source sends that a gathered receiver takes from its links: sent less
  // the source's own emission as sent (0 when sources send their emission alone).
  double reflected_sent(uint32_t source) const;
  double reflected_sent(const Link& l) const;

  // Unoccluded form factor estimate from centres (Hanrahan et al.: a disc of the source's area),
  // taking cosines as 1 when the two are close to each other's size (no trust in centre angles).
  double transfer_estimate(const HNode& ri, const HNode& sj) const;

  // The largest departure of the emitters' irradiance at a quarter of one of element i's children
  // from that child's mean (measure_variation; Link::inner bounds it).
  double emitted_inner(uint32_t i) const;

  // Mean max(cos, 0) over random orientations: a cluster's mean projected area is A/4 (Sillion 1995).
  static constexpr double kClusterCosine = 0.25;
  // Below this share of the white, the tolerance stops falling with the radiosity (dark surfaces are
  // held to an absolute error, not a relative one).
  static constexpr double kDarkShare = 0.1;
  // The white never falls below this share of the light's mean over the surfaces (emitted power over
  // their area, light_density). Where nearly all of a scene turns its back to the lights (a room of
  // one-sided slabs facing into themselves) the 95th percentile is dust, 1e-13 of the lights, and every
  // threshold relative to it passes: refinement runs to the minimum element everywhere light falls.
  static constexpr double kWhiteFloor = 0.1;
  double light_density() const;

  Hierarchy& h_;
  const HierarchicalSettings& s_;
  const double quantum_area_;
  bool importance_ = false;
  double seen_density_ = 0;
  mutable double light_density_ = -1;  // light_density(), once
  OracleState state_;
};

}  // namespace walkrad::hierarchical_detail
