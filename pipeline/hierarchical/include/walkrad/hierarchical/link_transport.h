// The transport operator that a hierarchy's links define between its leaves, applied outside the
// solver's sweeps, and the two corrections built on it:
//
//   T x at leaf i:  a_i Σ_{links (p ← q), p = i or an ancestor} F_pq · x̄_q,   x̄_q = area mean of s·x over q's leaves
//
// (a_i: the leaf's receive factor, s_j its send factor; both 1 unless balanced below).
//
// - balance_closed_transport: in a closed scene every leaf must receive a row sum of 1 (a furnace
//   stays uniform) and send all of its power (energy is conserved). Links between coarse nodes satisfy
//   neither exactly: pushed irradiance and area-averaged radiosity misplace transfer near corners (row
//   sums 0.80–1.25 in an empty box). The leaf-to-leaf matrix is scaled on both sides, diag(a) T diag(s),
//   by Sinkhorn–Knopp iteration (Sinkhorn & Knopp 1967): alternately a_i = 1 / (row sum) and
//   s_j = 1 / (power sent per unit emitted), until both hold.
// - aggregation_correction: the slowest mode of Gauss-Seidel at high reflectance is the scene's overall
//   level of reflected light; scaling the reflected radiosity v = B − E − ρD (D: punctual lights) by the 1 + c that zeroes the
//   area-weighted residual removes it (Chatelin & Miranker 1982; the same correction as the classic
//   solver's, gauss_seidel.h, here through the links).
#pragma once

#include <memory>
#include <vector>

#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad {

// A leaf's row sum well above 1 means it receives more than any enclosure could send it (coincident
// surfaces in the input): its irradiance is scaled back to a row sum of 1. See Sweeps::gather (src/sweeps.h).
// Balanced leaves are exempt: their factors make a Σ F s exactly 1, whatever a Σ F is (a receive
// factor of 2.6 against sources sending 0.38 would be clamped as coincident and lose that light).
constexpr double kMaxRowSum = 1.5;

inline bool is_leaf_element(const HNode& n) { return !n.cluster && n.child_count == 0; }

// The irradiance a leaf receives from H gathered along its own links and its ancestors' (row sum S):
// times its receive factor, scaled back above kMaxRowSum. clamped: set when scaled back.
Vec3 leaf_irradiance(const HNode& leaf, const Vec3& H, double row_sum, bool* clamped = nullptr);

// Whether a closed scene's leaf with this unscaled row sum is scaled to 1 (rows only: its receive factor
// is 1 / the sum): within [1/4, 4]. Outside it the leaf is a hidden or coincident piece, left as it is.
bool scalable_row(double raw_row);

// Each node's area mean of its leaf elements' emission as they send it (E × send): the part of Bt that
// is the sources' own emission, which the final gather takes at the vertices instead (final_gather.h).
std::vector<Vec3> emitted_as_sent(const Hierarchy& h);

// Each node's area mean of its leaf elements' receive factors.
std::vector<double> mean_receive(const Hierarchy& h);

// Recomputes every non-leaf node's B and Bt as the area means of its leaves' (Bt = B × send).
void pull_up_radiosity(Hierarchy& h);

struct BalanceStats {
  int iterations = 0;
  double row_error = 0, column_error = 0;  // largest |row sum − 1|, |sent / had − 1| over balanced leaves
  uint64_t unbalanced = 0;                 // leaves left alone: unscaled sums outside [1/4, 4]
};

// Sets every leaf's receive and send factors so that, in a closed scene, each leaf's row sum is 1 and
// it sends what it has. Ends with a row update (rows exact: a furnace is uniform). Factors bounded to
// [1/4, 4]; leaves whose unscaled sums lie outside that (hidden or coincident pieces) keep 1.
// Warm-started from the factors already there (a later round's links differ little).
BalanceStats balance_closed_transport(Hierarchy& h, double tolerance = 1e-9, int max_iterations = 25);

// Rows only, the default in a closed scene (balance_closed_transport is --effect closure=on): each leaf's
// receive factor is 1 / its row sum, so that it gathers as from a whole enclosure; send factors stay 1.
// Coarse links leave office-floor's leaves a mean row sum of 0.97 (area-weighted), and its visited
// rooms 2.9% too dark; scaled, 1.1% (see docs/numerics.md). Leaves whose raw row sum lies
// outside [1/4, 4] keep 1, and so do the leaves `unscaled` marks (under a close cluster pair left whole:
// Refinement::under_close_pairs). Returns the number of such leaves; mean_row: the area-weighted mean raw sum.
uint64_t normalise_closed_rows(Hierarchy& h, double* mean_row = nullptr, const std::vector<uint8_t>* unscaled = nullptr);

// What aggregation_correction fills, kept by a caller that corrects again and again (the solve's
// sweeps): made on every call, the node-sized arrays would be fresh pages, each 4 KiB a page fault
// (office-floor 32 rooms: 0.94 M of its bake's 2.6 M faults).
struct CorrectionBuffers {
  CorrectionBuffers();
  ~CorrectionBuffers();
  struct Held;
  std::unique_ptr<Held> held;
};

// One aggregation correction of the leaves' radiosity (indirect light on). Returns the largest
// change of a leaf's B relative to max(its B, floor); level, if given: the largest |c| of the three
// channels (how far the scene's overall reflected level was off). Updates B and Bt everywhere.
// buffers: kept between calls (none: its own, for this call).
double aggregation_correction(Hierarchy& h, double floor = 0, double* level = nullptr, CorrectionBuffers* buffers = nullptr);

}  // namespace walkrad
