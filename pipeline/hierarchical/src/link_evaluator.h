// Link evaluation, the part of the hierarchical solver (solver.h) that turns a pending link into an
// evaluated one: its form factor F, what its rays could have missed (σ), how it falls on the receiver's
// children (Link::share) and how much of the source's parts it sees (Link::seen), and whether its
// occlusion is proven. It reads the hierarchy and the rays and changes neither: pending links in,
// evaluated links out. Private to this stage.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "walkrad/core/huge_pages.h"
#include "walkrad/core/sampling.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/hierarchical/transmission.h"
#include "walkrad/visibility/occlusion_proof.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad::hierarchical_detail {

// A link the refinement asks for, as it asks (Pending's first fields): the round's list grows by
// doubling while the refinement runs, a quarter of the bytes a Pending would copy and fault in, and is
// made into Pendings once, at their exact count, when the round's links are evaluated (take_requests).
struct LinkRequest {
  uint32_t receiver, source;
  int32_t samples;
  bool need_rays, volume;
};
static_assert(sizeof(LinkRequest) == 16, "LinkRequest's size changed");

// A link found by the refinement, waiting for its form factor (evaluated in parallel).
// 64 bytes: a round's list is held beside every link while it is evaluated (80 with 64-bit counts;
// a link casts at most 8 × its samples, and those are at most the solver's recast factor × 65535: 32 bits hold it).
struct Pending {
  uint32_t receiver, source;
  int samples = 0;  // rays (or Monte Carlo samples) for this link
  bool need_rays;   // Embree rays (against the solid scene when volume)
  bool volume = false;  // volume clusters in the shaft stand in for their polygons (volume_visibility.h)
  uint8_t inner = 0;    // Link::inner
  bool proven = false;  // every ray blocked, and occlusion_proof.h proves every other would be: dropped
  double F = 0;
  float sigma = 0, open = 0;
  std::array<float, 4> share = {1, 1, 1, 1};
  std::array<uint16_t, 4> seen = {0, 0, 0, 0};
  uint32_t rays = 0, grid_segments = 0;

  explicit Pending(const LinkRequest& r)
      : receiver(r.receiver), source(r.source), samples(r.samples), need_rays(r.need_rays), volume(r.volume) {}
};
static_assert(sizeof(Pending) == 64, "Pending's size changed");
// A round's list, made afresh each round: on huge pages (core/huge_pages.h; on small pages, 0.25 M of
// the 150-room level's page faults are this list's).
using PendingList = HugeVector<Pending>;

// The punctual lights when the solve simulates them (null: none).
inline const std::vector<PunctualLight>* simulated_lights(const HierarchicalSettings& s) {
  return s.lights && !s.lights->empty() ? s.lights : nullptr;
}
// τ of an element's material when transmission is simulated (else 0). Inline: the sweeps ask it of
// every leaf, and most have no twin.
inline Vec3 simulated_transmittance(const Hierarchy& h, const HierarchicalSettings& s, const HNode& n) {
  if (!s.twins || n.cluster || (*s.twins)[n.polygon] == kNoTwin) return {};
  return material_transmittance(h, n);
}
// Whether a source acts as a lamp, its light set before the solve: it emits, or its material passes on
// what punctual lights give its back (a lamp's shade, lit from inside). Its links keep how their
// transfer varies inside the receiver's children (Link::inner): the table 10 cm under lamp-room's
// shade stayed one element under one link from it at --error 0.2 and read its mean (the test's
// points 6.0% RMS, 1.5% as a luminaire: LampShade.OutsideShowsTheBulbThroughIt).
bool luminaire(const Hierarchy& h, const HierarchicalSettings& s, const HNode& n);
// A cluster end within half its radius of the other end: a close pair, whose kernel the evaluation
// bounds (each sample a disc) and which the refinement splits where the display needs it.
bool close_pair(const Hierarchy& h, uint32_t i, uint32_t j);

class LinkEvaluator {
 public:
  // The hierarchy, the rays and the settings must outlive the evaluator.
  LinkEvaluator(const Hierarchy& h, const RayScene& rays, const HierarchicalSettings& s);

  // list[begin, end) evaluated in parallel. Each link draws from its own random stream (its two ends),
  // so a link's result is the same whatever the thread or rank that evaluates it.
  void evaluate_range(PendingList& list, size_t begin, size_t end) const;
  // One link; segments, visible and weights are scratch, kept between calls by the caller.
  void evaluate(Pending& p, std::vector<RayScene::Segment>& segments, std::vector<double>& visible,
                std::vector<double>& weights) const;

  // Cluster links whose ends hold at most this many polygon pairs get their unoccluded form factor
  // exactly (exact_unoccluded), the rest by Monte Carlo.
  static constexpr uint64_t kExactClusterPairs = 64;

 private:
  // What of each segment arrives: 0 or 1 from Embree (against the solid scene when the link sees
  // through volumes), times the transmittance through the extinction grid.
  void visibility(Pending& p, const std::vector<RayScene::Segment>& segments, std::vector<double>& visible) const;

  // A Monte Carlo sample of a link with a cluster receiver: which child of the receiver its point
  // lies in, which child of the source its other point lies in, its kernel (0 when the two points do
  // not face each other), its ray (−1: none).
  struct ClusterSample {
    uint32_t child, source_child;
    double value;
    int32_t segment;
  };

  // Element to element, by the receiver's quadrants (link_evaluation.cpp).
  void evaluate_elements(Pending& p, Rng& rng, std::vector<RayScene::Segment>& segments, std::vector<double>& visible) const;

  // Link::share for a cluster receiver, from its children's facing areas (HNode::facing).
  std::array<float, 4> cluster_shares(const HNode& ri, const HNode& sj) const;

  // Link::share from Monte Carlo samples, each tagged with the receiver child it lies in.
  static std::array<float, 4> child_shares(uint32_t children, const std::vector<ClusterSample>& samples,
                                           const std::vector<double>& visible, double F);

  // The form factor kernel between two surface points, cos θ cos θ' / r² (without the constant).
  static double point_kernel(const Vec3& x, const Vec3& nx, const Vec3& y, const Vec3& ny);

  uint64_t polygon_pairs(const HNode& a, const HNode& b) const;
  // (1/A_i) Σ_{k ∈ i} Σ_{m ∈ j} A_k F_km over the polygons (or the element) of each end.
  double exact_unoccluded(const HNode& ri, const HNode& sj) const;

  // Whether a link whose every segment was blocked is proven hidden (occlusion_proof.h), by the planes
  // of the first surfaces a few of its segments meet. Not through volumes (their light is attenuated,
  // never stopped).
  bool proven_hidden(const Pending& p, const std::vector<RayScene::Segment>& segments) const;
  static constexpr int kProofHints = 4;  // segments whose first hit names a plane to try

  const Hierarchy& h_;
  const RayScene& rays_;
  const OcclusionProof proof_;
  const HierarchicalSettings& s_;
};

}  // namespace walkrad::hierarchical_detail
