#include "walkrad/classic/southwell.h"

#include <algorithm>

namespace walkrad {

std::vector<Vec3> solve_southwell(const FormFactorMatrix& f, const std::vector<double>& area,
                                  const std::vector<Vec3>& reflectance, const std::vector<Vec3>& emission,
                                  const SouthwellSettings& settings, SouthwellStats& stats) {
  const size_t n = f.rows();
  stats = {};
  // The matrix by columns: who receives from j (F_ij, i in column j), in row order.
  std::vector<uint64_t> start(n + 1, 0);
  for (uint32_t c : f.column) ++start[c + 1];
  for (size_t j = 0; j < n; ++j) start[j + 1] += start[j];
  std::vector<uint32_t> receiver(f.column.size());
  std::vector<double> value(f.column.size());
  {
    std::vector<uint64_t> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < n; ++i)
      for (uint64_t k = f.row_start[i]; k < f.row_start[i + 1]; ++k) {
        const uint64_t slot = fill[f.column[k]]++;
        receiver[slot] = uint32_t(i);
        value[slot] = f.value[k];
      }
  }
  std::vector<Vec3> b = emission, unshot = emission;
  std::vector<double> power(n);  // A_j × luminance of ΔB_j
  double emitted = 0, total_area = 0;
  Vec3 mean_rho;
  for (size_t j = 0; j < n; ++j) {
    power[j] = area[j] * luminance(unshot[j]);
    emitted += power[j];
    total_area += area[j];
    mean_rho += reflectance[j] * area[j];
  }
  if (total_area > 0) mean_rho = mean_rho / total_area;
  const uint64_t max_shots = settings.max_shots > 0 ? settings.max_shots : 10000 * uint64_t(std::max<size_t>(n, 1));
  auto left = [&] {
    double sum = 0;
    for (double p : power) sum += p;
    return sum;
  };
  double remaining = emitted;
  while (emitted > 0 && stats.shots < max_shots) {
    // Every n shots the sum is taken afresh (the running one drifts by rounding).
    if (stats.shots % std::max<size_t>(n, 1) == 0) remaining = left();
    if (remaining <= settings.tolerance * emitted) {
      stats.converged = true;
      break;
    }
    const size_t j = size_t(std::max_element(power.begin(), power.end()) - power.begin());
    const Vec3 shot = unshot[j];
    unshot[j] = Vec3{};
    remaining -= power[j];
    power[j] = 0;
    for (uint64_t k = start[j]; k < start[j + 1]; ++k) {
      const uint32_t i = receiver[k];
      const Vec3 gained = mul(reflectance[i], shot) * value[k];
      b[i] += gained;
      unshot[i] += gained;
      const double p = area[i] * luminance(unshot[i]);
      remaining += p - power[i];
      power[i] = p;
    }
    ++stats.shots;
  }
  stats.unshot = emitted > 0 ? left() / emitted : 0.0;
  stats.converged = stats.converged || stats.unshot <= settings.tolerance;
  Vec3 unshot_power;
  for (size_t j = 0; j < n; ++j) unshot_power += unshot[j] * area[j];
  for (int c = 0; c < 3; ++c)
    stats.ambient[c] = total_area > 0 && mean_rho[c] < 1 ? unshot_power[c] / total_area / (1 - mean_rho[c]) : 0.0;
  if (settings.ambient)
    for (size_t i = 0; i < n; ++i) b[i] += mul(reflectance[i], stats.ambient);
  return b;
}

}  // namespace walkrad
