// The reference along a set of view rays (docs/accuracy.md): where each ray first meets a front face,
// and there B with its standard error (reference_tracer.h); a bake read back along the same rays; a
// reference image as PNG. Used by the sweep (sweep.h).
#pragma once

#include <string>
#include <vector>

#include "walkrad/accuracy/bake_sampler.h"
#include "walkrad/accuracy/reference_tracer.h"
#include "walkrad/accuracy/view_samples.h"

namespace walkrad {

// Luminance values are NaN where the ray escapes, meets a back face or an emitter (an emitter's B is
// its E, right in every bake, and would swamp the relative error).
struct ReferenceSet {
  std::vector<ViewRay> rays;
  std::vector<double> distance, luminance, standard_error, weight;
  std::vector<Vec3> B;  // for images; emitters hold E
  uint64_t rays_cast = 0;
  double seconds = 0;
};

// `samples` paths per point, seeded by `seed` (point k: stream k of the measured points).
ReferenceSet trace_reference(const Scene& scene, const RayScene& rays, const ReferenceTracer& tracer,
                             std::vector<ViewRay> view_rays, int samples, uint64_t seed);

// A bake's luminance of B along the reference's rays; NaN where the reference has none, or where the
// bake's first hit is more than `tolerance` from the reference's (a silhouette the meshes resolve
// differently).
std::vector<double> sample_bake(const BakeSampler& bake, const ReferenceSet& ref, double tolerance);

// A reference image as an sRGB PNG: display colour = B/π × exposure (the 95th percentile of the
// non-emitters → 0.9; emitters clip), rows top first. Throws OutputError.
void write_image_png(const std::string& path, const std::vector<Vec3>& B, const std::vector<double>& luminance,
                     int width, int height);

}  // namespace walkrad
