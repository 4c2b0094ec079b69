// Progressive refinement, the shooting form of the classic radiosity system (Cohen, Chen, Wallace &
// Greenberg 1988; Southwell's relaxation of the residual: the course's "méthode de Southwell"):
// each step shoots the element with the most unshot power, A_j ΔB_j: every receiver i that sees j
// gains ρ_i F_ij ΔB_j in its radiosity and in its own unshot radiosity, and j's unshot radiosity
// becomes 0. What is not shot yet is shown through the ambient term,
//   ambient = (Σ_j A_j ΔB_j / Σ_j A_j) / (1 − ρ̄),  ρ̄ the area mean of the reflectance,
// each element displayed as B_i + ρ_i × ambient: the unshot power spread evenly and interreflected.
// It stops when the unshot power is below tolerance × the emitted power (ambient included in the
// result). Sequential, ties to the lowest index: deterministic.
#pragma once

#include <vector>

#include "walkrad/classic/form_factor_matrix.h"

namespace walkrad {

struct SouthwellSettings {
  double tolerance = 1e-7;      // stop: unshot power / emitted power (luminance)
  uint64_t max_shots = 0;       // 0: 10,000 × the number of elements
  bool ambient = true;          // add the ambient term to the result
};

struct SouthwellStats {
  uint64_t shots = 0;
  double unshot = 0;            // unshot power / emitted power at the end
  bool converged = false;
  Vec3 ambient;                 // the ambient term at the end (W/m²)
};

std::vector<Vec3> solve_southwell(const FormFactorMatrix& f, const std::vector<double>& area,
                                  const std::vector<Vec3>& reflectance, const std::vector<Vec3>& emission,
                                  const SouthwellSettings& settings, SouthwellStats& stats);

}  // namespace walkrad
