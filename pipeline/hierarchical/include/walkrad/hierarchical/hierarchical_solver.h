// Hierarchical radiosity with clustering and importance (algorithms.md §5–7): Hanrahan, Salzman &
// Aupperle 1991 (links between nodes at the level where the transfer is accurate enough); Smits,
// Arvo & Salesin 1992 (importance emitted from the viewpoints, shot back along the same links, so
// that refinement goes where the walkthrough looks); Smits, Arvo & Greenberg 1994 and Sillion 1995
// (clusters as isotropic volumes of small surfaces: mean projected area A/4).
//
// The loop starts from one link of the root cluster to itself, linked down only as far as clusters
// must be (a cluster closer to the other end than half its radius), and repeats
//   evaluate:  new links' form factors with visibility (shaft culling, then Embree rays), in parallel,
//              each with how its transfer falls on the receiver's children and its standard error;
//   solve:     gather H_i = Σ F_ij B_j along links (Gauss-Seidel by input polygon, or Jacobi), push-pull
//              (irradiance pushed down, B = E + ρH at the leaves, B area-averaged up), and importance
//              shot along the same links (I_j += ρ_i F_ij I_i), pushed down by area and summed up;
//   refine:    measure the error each receiver is left with (error_estimate.cpp): the variation of its
//              transfers over its children, the sources' unresolved detail, the estimates' noise;
//              where it exceeds the tolerance, e × what the receiver shows / its display weight (the
//              importance from the views; 1 without), split the receiver or the source;
// until no link is refined and the radiosity stops changing.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/hierarchical/error_presets.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/visibility/volume_visibility.h"

namespace walkrad {

// A sample of a solve's Embree rays, for benchmarks (bench/level_rays_bench.cpp: the solve's rays per
// second against a bare loop over the same rays): the segments of every link whose (receiver, source)
// hash falls in one of `every` buckets, appended as links are evaluated (their order varies with the
// threads; what is sampled does not).
struct RaySample {
  uint32_t every = 1024;
  std::mutex lock;
  std::vector<RayScene::Segment> segments;
  std::vector<size_t> link_begin;  // where each sampled link's segments start (one call each in the solve)
};

struct HierarchicalSettings {
  double error = kDefaultError;  // tolerance, relative to what each surface shows (error_estimate.cpp)
  bool use_importance = true; // weigh tolerances by importance when the hierarchy has view hits
  double min_area = 0;        // m²; elements are not split below it (0: default_min_area)
  int max_depth = 16;         // quadtree levels below an input polygon
  int rays = 16;              // visibility rays (or Monte Carlo samples) per link, ×2 with more than 4
                              // candidate occluders, ×4 with more than 64
  double tolerance = 1e-5;    // stop: largest relative change of a leaf's B between sweeps, × its display weight
  int max_iterations = 64;    // refine + solve rounds
  // Gather/push-pull sweeps per round but the last (which sweeps to the tolerance). They only steer the
  // next refinement: with 2 rather than 4 the 150-room level takes 162.9 s against 180.5 s, and every
  // accuracy scene's error stays within its noise (4 → 2: visited rooms 3.15 → 3.10%, office-floor
  // 8 rooms 2.03 → 2.08%, the hospital 5.07 → 4.79%).
  int sweeps = 2;
  // A pair about to be split whose parent pair's candidate list holds more entries than this is first
  // probed with `rays` rays, and linked instead where all are blocked (pair_refinement.cpp). 4,096
  // probes pairs rooms apart: the 150-room level's 839 pairs (512 hidden), its solve 124 s against
  // 176 s unprobed, at the same error.
  size_t probe_entries = 4096;
  bool gauss_seidel = true;   // gather each polygon's quadtree with this sweep's values (else Jacobi)
  // Gauss-Seidel: runs of polygons and clusters none of which reads what another's push changes
  // gather together, in parallel (solve_sweep.cpp): the same bits as one at a time, which false keeps
  // for the tests' comparison.
  bool gather_blocks = true;
  // The last round's Gauss-Seidel sweeps, once two plain ones past its first `sweeps` show slow modes
  // (hierarchical_solver.cpp), over-relax each leaf's gathered irradiance, H ← H_before + ω (H_gathered
  // − H_before) (successive over-relaxation; Cohen & Wallace 1993, ch. 5), the aggregation correction
  // having taken the overall mode: office-floor's last round 20 → 14 sweeps at 32 rooms, 12 → 10 at
  // 150 and 11 → 9 at 8 (plain → over-relaxed). 1: plain.
  double relaxation = 1.4;
  bool visibility = true;     // false: no occlusion possible (effect plan): no shafts' rays
  bool indirect = true;       // false: gather only the sources' emission (direct light, one bounce)
  // The scene is closed (effect plan: no ray escapes): every leaf must receive a row sum of 1 and
  // send all of its power B·A, which coarse links satisfy only roughly (they push irradiance
  // uniformly and take radiosity by area: row sums 0.80–1.25 in an empty lit box, which lost 2.7% of
  // its power). Closed: both are restored by scaling each leaf's gather and send (link_transport.h).
  bool closed = false;
  // Closed, but not balanced: each leaf's row sum alone is scaled to 1 (normalise_closed_rows).
  bool closed_rows = false;
  // Aggregation correction after every sweep (link_transport.h): removes the slow overall mode of
  // Gauss-Seidel at high reflectance (furnace ρ 0.99: 611 sweeps without).
  bool accelerate = true;
  // Punctual lights (punctual_lights.h), shot straight to the elements: an element is split while the
  // irradiance they give varies over it by more than its tolerance allows (ρ · spread). Not owned.
  const std::vector<PunctualLight>* lights = nullptr;
  // Transmission twins per polygon (walkrad/scene/transmission_twins.h; kNoTwin: none): a leaf of a transmitting polygon
  // adds τ × what its twin receives at its centroid. No aggregation correction then. Not owned.
  const std::vector<uint32_t>* twins = nullptr;
  // The final gather (final_gather.h) evaluates the area emitters' direct light at the output vertices
  // of these input polygons (1: gathered; null: all of them, when gather is on): there the links bring
  // only what the sources reflect, and the error estimate measures only that; the refinement still
  // measures everything the links carry (error_estimate.cpp). Not owned.
  bool gather = false;
  const std::vector<uint8_t>* gathered = nullptr;
  // Volumetric visibility through volume clusters (volume_visibility.h); null: exact rays only. Not owned.
  const VolumeVisibility* volumes = nullptr;
  // Called between steps of a round (every 4,096 receivers of a refinement pass, before and after
  // the new links are evaluated, and before the list of new links grows: `more` bytes about to be
  // allocated, else 0), never from worker threads: the bake's memory cap (bake_caps.h) throws from
  // here, so that a round cannot run past it. Empty: nothing.
  std::function<void(const char* where, uint64_t more)> check_limits;
  // The bake's overall estimate of its error from the nodes' HNode::error (the bake's own measure,
  // relative RMS where the walkthrough looks), asked after every round of a solve past
  // estimate_from_links once the errors are measured: the progress shows what each round bought, and refinement ends where
  // it stops buying accuracy (refinement_stalled). Unset: measured once, after the last round.
  std::function<double()> estimate;
  // From how many links the rounds are estimated: each estimate is a pass over the links, which the
  // Cornell box's 0.2 s solve (150 k links) paid with 15-23% more CPU; diminishing returns matter where
  // refinement takes minutes.
  uint64_t estimate_from_links = 1'000'000;
  // Checkpoints (solve_checkpoint.cpp): after each round, save_round gets the rounds done so far and
  // a function that writes the solve's state to a ByteWriter (called or not, as it likes); resume, a
  // state so written, is read (ByteFormatError where it does not fit) and started from instead of
  // the first round.
  std::function<void(int rounds, const std::function<void(ByteWriter&)>& write_state)> save_round;
  ByteReader* resume = nullptr;
  // Benchmarks only: where to put a sample of the solve's rays (RaySample). Null: nothing. Not owned.
  RaySample* ray_sample = nullptr;
};

struct IterationStats {
  uint64_t links = 0, new_links = 0, elements = 0, rays = 0;
  double change = 0;                   // largest relative change of B at the leaves (× display weight)
  int sweeps = 0;                      // gather/push-pull sweeps this round
  Vec3 emitted, absorbed;              // W, at the leaves
  Vec3 residual;                       // W: Σ A |E + ρH − B| over the leaves, before the last sweep
  uint64_t clamped_leaves = 0;         // leaves whose row sum Σ F exceeded 1.5 (irradiance scaled back)
  uint64_t bytes_exchanged = 0;        // under mpirun: bytes this rank sent and received this round (ranks.h)
  uint64_t sweep_bytes = 0;            // of which in its sweeps (a divided solve's node values, link_owners.h)
  double estimated_error = -1;         // HierarchicalSettings::estimate after the round (−1: not asked)
};

// Diminishing returns, the bound on a bake's refinement where more links no longer buy accuracy: the
// round just solved (now, after `rounds`) holds at least kStallGrowth times the links of the round two
// before it, and its estimated error (IterationStats::estimated_error) fell, but by less than kStallGain
// of that round's. Rounds without an estimate never stall. On RenderPark's office1 (graz.mgf) rounds 5 to
// 7 doubled the links (14.7 M to 30.6 M) for 14% less error (3.45% to 2.98%), and round 8 took them
// to 56.0 M; the Cornell box's last rounds add 4 to 15% each.
constexpr double kStallGrowth = 2.0, kStallGain = 0.15;
bool refinement_stalled(const std::vector<IterationStats>& rounds, const IterationStats& now);

struct HierarchicalStats {
  std::vector<IterationStats> iterations;
  uint64_t links = 0, rays = 0, unoccluded_links = 0, monte_carlo_links = 0;
  uint64_t refinements = 0;            // links split
  uint64_t receiver_splits = 0;        // receivers whose links went down to their children (variation)
  uint64_t recast = 0;                 // wholly hidden links cast again with more rays
  uint64_t proven_hidden = 0;          // links every ray of which was blocked, proven hidden and dropped
  uint64_t probed_pairs = 0, probe_hidden = 0, probe_rays = 0;  // pairs probed before a split, with rays cast (Refinement::probe)
  bool converged = false;
  int64_t stalled_round = -1;          // the round after which refinement stopped, its returns diminished (refinement_stalled)
  std::string oracle;                  // "importance" or "view-independent"
  double white = 0;                    // the display white the tolerances were relative to (W/m²)
  double min_area = 0;                 // the smallest element allowed (m²)
  uint64_t above_tolerance = 0;        // receivers left above their tolerance (at the minimum area)
  int corrections = 0;                 // aggregation corrections applied
  uint64_t light_rays = 0;             // shadow rays towards punctual lights
  uint64_t light_refinements = 0;      // elements split for the punctual lights' variation
  int balance_iterations = 0;          // Sinkhorn iterations (closed scenes), all rounds
  double mean_row_sum = 0;             // closed_rows: the leaves' area-weighted mean raw row sum, last round
  double balance_row_error = 0, balance_column_error = 0;  // after the last balance
  uint64_t balance_unbalanced = 0;     // leaves the last balance left alone (hidden, coincident)
  // Visibility per link: unoccluded_links (nothing in the shaft), exact_links (Embree rays against
  // every polygon), volume_links (volume clusters as media, volume_visibility.h: transmittance through
  // the grid, rays against the rest if anything else is in the shaft).
  uint64_t exact_links = 0, volume_links = 0;
  uint64_t grid_segments = 0;          // transmittance integrations through the extinction grid
  // The most bytes links and the round's list of new links took at once (on this rank: a divided
  // solve keeps only its receivers' links, link_owners.h), and whether the links were divided.
  uint64_t link_bytes_peak = 0;
  bool divided = false;
};

// Why a solve over several ranks keeps every link on every rank instead of dividing them
// (link_owners.h), or null where it divides them. indivisible_because: the settings whose steps read
// links across polygons (Gauss-Seidel sweeps, the closure balance, transmission); undivided_because
// adds checkpoints, whose file holds every link (their solve is still the divided one's).
const char* indivisible_because(const HierarchicalSettings& s);
const char* undivided_because(const HierarchicalSettings& s);

// The default smallest element: the median input polygon's side / 128, squared, the median by area or, where
// smaller, by what the walkthrough sees of each polygon (its direct importance).
double default_min_area(const Hierarchy& h);

// progress(message) is called after each round (may be empty).
void solve_hierarchical(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& settings, HierarchicalStats& stats,
                        const std::function<void(const IterationStats&)>& progress = {});

}  // namespace walkrad
