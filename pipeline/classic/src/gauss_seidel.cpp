#include "walkrad/classic/gauss_seidel.h"

#include <algorithm>
#include <cmath>

namespace walkrad {

namespace {

Vec3 gather(const FormFactorMatrix& f, size_t i, const std::vector<Vec3>& b) {
  Vec3 h;
  for (uint64_t k = f.row_start[i]; k < f.row_start[i + 1]; ++k) h += b[f.column[k]] * f.value[k];
  return h;
}

Vec3 abs3(const Vec3& v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }

// The aggregation correction (see the header): scales the reflected light v = B − E by 1 + c. Returns
// the largest relative change it made.
double correct(const FormFactorMatrix& f, const std::vector<double>& area, const std::vector<Vec3>& reflectance,
               const std::vector<Vec3>& emission, std::vector<Vec3>& b) {
  const size_t n = f.rows();
  std::vector<Vec3> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = b[i] - emission[i];
  Vec3 num, den, total;
  for (size_t i = 0; i < n; ++i) {
    const double a = area.empty() ? 1.0 : area[i];
    num += (emission[i] + mul(reflectance[i], gather(f, i, b)) - b[i]) * a;
    den += (v[i] - mul(reflectance[i], gather(f, i, v))) * a;
    total += v[i] * a;
  }
  Vec3 c;
  for (int k = 0; k < 3; ++k)
    if (den[k] > 1e-12 * total[k]) c[k] = std::max(-0.5, num[k] / den[k]);
  double largest = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 next = b[i] + mul(c, v[i]);
    const double scale = max_component(next);
    if (scale > 0) largest = std::max(largest, max_component(abs3(next - b[i])) / scale);
    b[i] = next;
  }
  return largest;
}

}  // namespace

std::vector<Vec3> solve_gauss_seidel(const FormFactorMatrix& f, const std::vector<Vec3>& reflectance,
                                     const std::vector<Vec3>& emission, const SolveSettings& settings, SolveStats& stats) {
  return solve_gauss_seidel(f, {}, reflectance, emission, settings, stats);
}

std::vector<Vec3> solve_gauss_seidel(const FormFactorMatrix& f, const std::vector<double>& area,
                                     const std::vector<Vec3>& reflectance, const std::vector<Vec3>& emission,
                                     const SolveSettings& settings, SolveStats& stats) {
  const size_t n = f.rows();
  std::vector<Vec3> b = emission;
  stats = {};
  while (stats.iterations < settings.max_iterations) {
    // Each element's update relative to its own value: dim elements converge as tightly as bright
    // ones (a scale set by the brightest would stop while indirect light is still far off).
    double largest = 0;
    for (size_t i = 0; i < n; ++i) {
      const Vec3 next = emission[i] + mul(reflectance[i], gather(f, i, b));
      const double scale = max_component(next);
      if (scale > 0) largest = std::max(largest, max_component(abs3(next - b[i])) / scale);
      b[i] = next;
    }
    if (settings.accelerate) {
      largest = std::max(largest, correct(f, area, reflectance, emission, b));
      ++stats.corrections;
    }
    ++stats.iterations;
    stats.last_update = largest;
    if (stats.last_update <= settings.tolerance) {
      stats.converged = true;
      break;
    }
  }
  return b;
}

EnergyBalance energy_balance(const FormFactorMatrix& f, const std::vector<double>& area, const std::vector<Vec3>& reflectance,
                             const std::vector<Vec3>& emission, const std::vector<Vec3>& radiosity) {
  EnergyBalance e;
  for (size_t i = 0; i < f.rows(); ++i) {
    const Vec3 h = gather(f, i, radiosity);
    e.emitted += emission[i] * area[i];
    e.absorbed += mul(Vec3(1, 1, 1) - reflectance[i], h) * area[i];
    e.residual += abs3(emission[i] + mul(reflectance[i], h) - radiosity[i]) * area[i];
  }
  return e;
}

}  // namespace walkrad
