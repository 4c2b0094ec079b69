// Gauss-Seidel gathering for the classic radiosity system (algorithms.md §4):
//   B_i ← E_i + ρ_i Σ_j F_ij B_j, using fresh values as soon as they are computed.
// Converges since ‖ρF‖∞ ≤ ρ_max < 1. Sequential in element order, so deterministic.
#pragma once

#include <vector>

#include "walkrad/pipeline/form_factor_matrix.h"

namespace walkrad {

struct SolveSettings {
  double tolerance = 1e-7;   // stop when every element's update is below tolerance × its B
  int max_iterations = 10000;
};

struct SolveStats {
  int iterations = 0;
  double last_update = 0;    // largest |ΔB_i| / B_i of the last sweep
  bool converged = false;
};

std::vector<Vec3> solve_gauss_seidel(const FormFactorMatrix& f, const std::vector<Vec3>& reflectance,
                                     const std::vector<Vec3>& emission, const SolveSettings& settings, SolveStats& stats);

// Power balance of a solution (W): emitted Σ A E, absorbed Σ A (1-ρ) H with H = Σ F B, and the
// residual Σ A |E + ρH − B|. In a closed scene emitted = absorbed at convergence.
struct EnergyBalance {
  Vec3 emitted, absorbed, residual;
};
EnergyBalance energy_balance(const FormFactorMatrix& f, const std::vector<double>& area, const std::vector<Vec3>& reflectance,
                             const std::vector<Vec3>& emission, const std::vector<Vec3>& radiosity);

}  // namespace walkrad
