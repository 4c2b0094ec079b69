// Monte Carlo form factor with visibility and an error bar (algorithms.md §3, "With occlusion";
// Cohen & Wallace 1993, §4.9.4): the mean of N independent samples of
//   k(x, y) = cosθ_x cosθ_y / (π r²) · v(x, y) · A_j
// with x uniform on the receiver i and y uniform on the source j, whose expectation is F_ij.
// Samples are independent (not stratified) so that the sample variance gives an honest standard
// error; std_error shrinks as 1/sqrt(N) while the kernel's variance is finite.
#pragma once

#include <cstdint>

#include "walkrad/formats/scene.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

struct MonteCarloEstimate {
  double value = 0;      // the estimate of F_ij
  double std_error = 0;  // the estimated standard deviation of `value` (sample std. dev. / sqrt(N))
  uint64_t samples = 0;
};

// F_ij from receiver i to source j. Only the front sides exchange light (cosθ <= 0 counts 0).
// occluders: null for unoccluded; otherwise each sample casts one ray between x and y, both moved
// off their surfaces by occluders->offset() along their polygons' normals, so the receiver and the
// source may themselves be in the RayScene. Deterministic for a given seed, whatever the thread count.
// Caveat: where the polygons touch (a floor and a wall sharing an edge) k ~ 1/r² has infinite
// variance: the estimate stays unbiased, but its error shrinks only as about N^(-1/3), rare huge
// samples dominate, and std_error cannot be trusted. Use the control-variate form below there.
MonteCarloEstimate form_factor_monte_carlo(const Polygon& receiver, const Polygon& source, const RayScene* occluders,
                                           uint64_t samples, uint64_t seed);

// The same expectation with the exact unoccluded point form factor as a control variate
// (point_to_polygon, Lambert's contour formula):
//   F_ij = E_x[ F_dA(x)→j − A_j k(x, y) (1 − v(x, y)) ],
// so only occluded samples carry the singular kernel: touching pairs keep a finite variance (unless
// an occluder reaches into their junction) and std_error holds again. Without occluders it reduces to
// Monte Carlo over x alone. Costs a point_to_polygon per sample; same arguments and guarantees.
MonteCarloEstimate form_factor_monte_carlo_control_variate(const Polygon& receiver, const Polygon& source,
                                                           const RayScene* occluders, uint64_t samples,
                                                           uint64_t seed);

}  // namespace walkrad
