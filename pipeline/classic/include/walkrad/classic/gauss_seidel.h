// Gauss-Seidel gathering for the classic radiosity system (algorithms.md §4):
//   B_i ← E_i + ρ_i Σ_j F_ij B_j, using fresh values as soon as they are computed.
// Converges since ‖ρF‖∞ ≤ ρ_max < 1, but slowly when ρ is near 1: the error of the scene's overall
// brightness shrinks by only ≈ ρ a sweep (ρ = 0.99: ~1,600 sweeps to 1e-7). So each sweep is followed
// by an aggregation correction (Chatelin & Miranker 1982; the idea of Cohen et al. 1988's ambient
// term, made exact): the reflected light v = B − E is scaled by (1 + c) per channel, with c chosen so
// that the corrected solution balances power over the whole scene,
//   Σ A (E + ρF(B + cv) − (B + cv)) = 0   ⇒   c = Σ A r / Σ A (v − ρFv),  r = E + ρFB − B.
// In a furnace this is the exact answer after one sweep; elsewhere it removes the slow global mode
// and Gauss-Seidel the local ones. c ≥ −1/2 keeps B ≥ E ≥ 0. Sequential in element order, so
// deterministic.
#pragma once

#include <vector>

#include "walkrad/classic/form_factor_matrix.h"

namespace walkrad {

struct SolveSettings {
  double tolerance = 1e-7;   // stop when every element's update is below tolerance × its B
  int max_iterations = 10000;
  bool accelerate = true;    // aggregation correction after each sweep (above)
};

struct SolveStats {
  int iterations = 0;
  double last_update = 0;    // largest |ΔB_i| / B_i of the last sweep
  bool converged = false;
  int corrections = 0;       // sweeps followed by an aggregation correction
};

// area: element areas (weights of the correction's power balance); empty weighs elements alike.
std::vector<Vec3> solve_gauss_seidel(const FormFactorMatrix& f, const std::vector<double>& area,
                                     const std::vector<Vec3>& reflectance, const std::vector<Vec3>& emission,
                                     const SolveSettings& settings, SolveStats& stats);
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
