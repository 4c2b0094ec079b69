// ReferenceTracer: an independent Monte Carlo estimate of diffuse radiosity at surface points, to
// check the radiosity solvers against (docs/accuracy.md). It shares no solver code with them: no
// form factors, no hierarchy, no mesh; only the scene arrays and Embree rays (RayScene).
//
// The rendering equation restricted to diffuse surfaces (Kajiya 1986; Dutré, Bekaert & Bala,
// "Advanced Global Illumination", ch. 5): B(x) = E(x) + ρ(x)·H(x), with irradiance
// H(x) = ∫ B(y)/π · cos θ dω over the hemisphere, B(y) the radiosity of the first front face seen
// (back faces and escaping rays bring nothing, as in the solvers; a material that transmits diffusely
// has two sides, and what leaves one is ρ × its irradiance + τ × the other side's). Estimated per path:
//  - next-event estimation: one point drawn uniformly on an emitter, E(y)/π · cos θx cos θy / r² /
//    pdf(y), Embree shadow ray; the emitter chosen at each path vertex x by its power over its distance
//    squared, P / (d² + A), and not where it lies wholly behind x or x behind it (a light in the next
//    room is drawn as often as one the same distance away in this room: unbiased, but a level of many
//    rooms no longer spends its samples on lights a building away); by power alone past kSpatialEmitters;
//  - a cosine-weighted direction (pdf cos θ / π, so the estimate of H is B(y) itself): the emitted
//    part E(y) when it meets an emitter, then the reflected part ρ(y)·H(y), recursively;
//  - the two estimates of emitted light combined by multiple importance sampling (Veach & Guibas
//    1995, power heuristic): near an emitter's edge, where next-event estimation's 1/r² would give
//    unbounded variance, the cosine-weighted sample takes over;
//  - punctual lights (KHR_lights_punctual), which no ray can meet: at every path vertex, each light's
//    I · falloff · cos θ / r² with a shadow ray, written from the extension's text;
//  - Russian roulette after three bounces, survival = the path's throughput (≤ 0.95).
// Every point draws from its own stream (Rng(seed, point)): results do not depend on the threads.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/visibility/ray_scene.h"
#include "walkrad/core/sampling.h"

namespace walkrad {

struct SurfacePoint {
  uint32_t polygon = 0;  // index into the scene's polygons
  Vec3 position;
};

// The mean of n path samples per channel and its standard error σ/√n (95% CI: ± 1.96 σ/√n).
struct RadiosityEstimate {
  Vec3 B;
  Vec3 standard_error;
  double luminance_error = 0;  // standard error of the luminance of B (samples' luminances)
  uint32_t samples = 0;
};

struct ReferenceSettings {
  int samples = 1024;      // paths per point
  uint64_t seed = 0x5EED;
};

class ReferenceTracer {
 public:
  // The scene and ray scene must outlive the tracer; rays is built from the same polygons.
  ReferenceTracer(const Scene& scene, const RayScene& rays);

  // One point, `samples` paths, from stream (seed, stream).
  RadiosityEstimate estimate(const SurfacePoint& point, int samples, uint64_t seed, uint64_t stream,
                             uint64_t& rays) const;

  // Every point in parallel (TBB); point k uses stream k. Adds the rays cast to `rays`.
  std::vector<RadiosityEstimate> estimate(const std::vector<SurfacePoint>& points, const ReferenceSettings& settings,
                                          uint64_t& rays) const;

  // Past this many emitting polygons, emitters are chosen by power alone (the choice costs a pass over them).
  static constexpr size_t kSpatialEmitters = 4096;

 private:
  // How likely next-event estimation at a path vertex is to choose each emitter (probabilities, by
  // emitter index): selection() fills it for x, normal n.
  struct Choice {
    std::vector<double> cdf;  // cumulative, last = 1 (empty: no emitter can light x)
    double of(size_t k) const { return cdf.empty() ? 0.0 : cdf[k] - (k ? cdf[k - 1] : 0.0); }
  };
  void selection(const Vec3& x, const Vec3& n, Choice& choice) const;
  Vec3 direct(const Vec3& x, const Vec3& n, const Choice& choice, Rng& rng, uint64_t& rays) const;
  Vec3 punctual(const Vec3& x, const Vec3& n, Rng& rng, uint64_t& rays) const;
  void scatter(const Material& m, Vec3& n, Vec3& beta, Rng& rng) const;
  // The solid-angle pdf with which next-event estimation at the vertex of `choice` draws a point of
  // `polygon` at distance² r2.
  double light_pdf(const Choice& choice, uint32_t polygon, double r2, double cos_y) const;

  const Scene& scene_;
  const RayScene& rays_;
  std::vector<Vec3> normals_;        // unit, per polygon
  std::vector<uint32_t> emitters_;   // emitting polygons
  std::vector<int32_t> emitter_index_;  // per polygon: its index in emitters_, or -1
  std::vector<double> emitter_cdf_;  // by power (luminance of E × area), normalised, last = 1
  std::vector<double> emitter_area_, emitter_power_;
  std::vector<Vec3> emitter_centre_;
};

}  // namespace walkrad
