// The classic method's run inside a bake (bake.cpp): subdivide, form factors, solve, audit.
#include <algorithm>
#include <cmath>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "method_run.h"
#include "walkrad/classic/form_factor_matrix.h"
#include "walkrad/classic/gauss_seidel.h"
#include "walkrad/classic/southwell.h"
#include "walkrad/classic/matrix_audit.h"
#include "walkrad/classic/subdivision.h"
#include "walkrad/core/progress.h"
#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/output/element_mesher.h"
#include "walkrad/scene/texture_sampling.h"
#include "walkrad/visibility/exposure.h"

namespace walkrad::bake_detail {

namespace {

// Element of `polygon` whose centroid is nearest to p (elements of a polygon are contiguous).
size_t element_at(const Subdivision& sub, uint32_t polygon, const Vec3& p) {
  size_t best = sub.first_element[polygon];
  double best_d = INFINITY;
  for (size_t e = sub.first_element[polygon]; e < sub.first_element[polygon + 1]; ++e) {
    const double d = dot(sub.elements[e].centroid - p, sub.elements[e].centroid - p);
    if (d < best_d) { best_d = d; best = e; }
  }
  return best;
}

}  // namespace

MethodResult run_classic(const BakeSettings& s, const Scene& scene, const RayScene& rays, const ClusterTree& tree,
                           const Bounds& bounds, const EffectPlan& plan, Phases& phases) {
  phases.start("subdivide");
  const double element_size = s.element_size > 0 ? s.element_size : length(bounds.diagonal()) / 30.0;
  auto sub = std::make_shared<Subdivision>(subdivide_uniform(scene, element_size));
  const size_t n = sub->elements.size();

  phases.start("form factors");
  FormFactorSettings ffs;
  ffs.rays_per_point = std::max(1, s.rays_per_point);
  ffs.visibility = plan.visibility.on;
  if (s.form_factors == FormFactors::hemicube) ffs.hemicube = s.hemicube_resolution;
  FormFactorCounts counts;
  FormFactorMatrix f;
  {
    Progress progress("form factors", n, s.progress);
    f = compute_form_factors(*sub, &rays, &tree, ffs, counts, [&](size_t done) {
      phases.check("form factors");
      progress.update(done);
    });
  }

  phases.start("solve");
  std::vector<Vec3> rho(n), emission(n), direct(n);
  std::vector<double> area(n);
  uint64_t light_rays = 0;
  if (plan.punctual.on) {  // punctual lights: each element's irradiance, 4 × 4 points (punctual_lights.h)
    std::vector<uint64_t> cast(n, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i)
        direct[i] = direct_irradiance(sub->elements[i].shape, scene.lights, plan.visibility.on ? &rays : nullptr, 4, cast[i]).mean;
    });
    for (uint64_t c : cast) light_rays += c;
  }
  for (size_t i = 0; i < n; ++i) {
    const Material& m = scene.materials[sub->elements[i].shape.material];
    SurfaceColour c{m.reflectance, m.emission};
    if (plan.textures.on) c = element_colour(scene, sub->elements[i].shape);
    rho[i] = c.reflectance;
    // What punctual lights give an element, it reflects like emitted light: E + ρ D.
    emission[i] = c.emission + mul(c.reflectance, direct[i]);
    area[i] = sub->elements[i].area;
  }
  SolveSettings solve;
  solve.tolerance = s.tolerance;
  solve.max_iterations = s.max_iterations;
  SolveStats stats;
  SouthwellStats shooting;
  auto b = std::make_shared<std::vector<Vec3>>();
  if (plan.indirect.on && s.solver == Iteration::southwell) {
    SouthwellSettings sw;
    sw.tolerance = s.tolerance;
    *b = solve_southwell(f, area, rho, emission, sw, shooting);
    stats.converged = shooting.converged;
    stats.last_update = shooting.unshot;
  } else if (plan.indirect.on) {
    *b = solve_gauss_seidel(f, area, rho, emission, solve, stats);
  } else {  // direct light only: B = E + ρ (F E + D), one gather of the surfaces' own emission
    b->resize(n);
    for (size_t i = 0; i < n; ++i) {
      Vec3 h;
      for (uint64_t k = f.row_start[i]; k < f.row_start[i + 1]; ++k)
        h += scene.materials[sub->elements[f.column[k]].shape.material].emission * f.value[k];
      (*b)[i] = emission[i] + mul(rho[i], h);
    }
    stats.iterations = 1;
    stats.converged = true;
  }
  const EnergyBalance energy = energy_balance(f, area, rho, emission, *b);
  for (const Vec3& v : *b)
    if (!is_finite(v)) throw std::runtime_error("the solution is not finite (please report this scene)");

  MethodResult r;
  r.radiosity_at = [sub, b](uint32_t poly, const Vec3& p) { return (*b)[element_at(*sub, poly, p)]; };
  r.mesh = [sub, b](double exposure, json&, json&) { return mesh_elements(*sub, *b, exposure); };
  std::vector<double> lum;
  for (size_t i = 0; i < n; ++i)
    if (!scene.materials[sub->elements[i].shape.material].emits()) lum.push_back(luminance((*b)[i]) / kPi);
  r.surface_exposure = exposure_for(std::move(lum));
  r.counts = {{"elements", n}, {"form_factor_pairs", counts.pairs}, {"unoccluded_pairs", counts.unoccluded},
              {"form_factor_entries", counts.nonzero}, {"visibility_rays", counts.rays}, {"iterations", stats.iterations},
              {"corrections", stats.corrections}, {"light_rays", light_rays}};
  r.solver = {{"element_size", element_size}, {"form_factors", form_factors_name(s.form_factors)}, {"iteration", s.solver == Iteration::southwell ? "southwell" : "gauss-seidel"},
              {"converged", stats.converged}, {"last_update", stats.last_update}, {"tolerance", s.tolerance}};
  if (s.solver == Iteration::southwell) {
    r.counts["shots"] = shooting.shots;
    r.solver["unshot"] = shooting.unshot;
    r.solver["ambient"] = vec_json(shooting.ambient);
  }
  r.energy = energy_json(energy.emitted, energy.absorbed);
  r.energy["residual_w"] = vec_json(energy.residual);
  r.audit = audit_json(audit_matrix(f, area, rho, emission, *b));
  return r;
}

}  // namespace walkrad::bake_detail
