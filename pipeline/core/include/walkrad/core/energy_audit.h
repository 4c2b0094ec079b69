// Energy audit of a radiosity solution (algorithms.md §4; Cohen & Wallace 1993, ch. 2), in watts:
//
//   emitted = absorbed + residual,   residual = escaped + unconverged
//
// per element of area A, reflectance ρ, emission E and radiosity B, with irradiance H = Σ_j F_ij B_j
// gathered afresh from the solution and row sum S = Σ_j F_ij:
//   emitted      Σ A E
//   absorbed     Σ A (1 − ρ) H
//   escaped      Σ A B (1 − S)      light that leaves through openings (≈ 0 in a closed scene)
//   unconverged  Σ A (E + ρH − B)   the solver's own remainder (signed)
// The identity holds exactly when the discrete form factors are reciprocal (A_i F_ij = A_j F_ji);
// `imbalance` is what it misses, relative to the emitted power: light created or lost by the
// discretisation (or by the solver). It is what the bake's report calls "energy_audit".
// Each method audits its own solution (walkrad/classic/matrix_audit.h, walkrad/hierarchical/hierarchy_audit.h).
// Sums run in element order in double precision: the same numbers whatever the thread count.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "walkrad/formats/scene.h"

namespace walkrad {

struct EnergyAudit {
  Vec3 emitted, absorbed, escaped, unconverged;
  Vec3 residual() const { return escaped + unconverged; }
  // max over channels of |emitted − absorbed − residual| / emitted (0 when nothing is emitted)
  double imbalance() const;
};

// One element's share, for solvers that hold their solution in other shapes.
struct AuditElement {
  double area = 0;
  Vec3 rho, emission, B, H;
  double row_sum = 0;  // the fraction of its radiosity that its links carry away (matrix: its row sum, by reciprocity)
  Vec3 direct = {};    // irradiance from punctual lights (counted as emitted where it lands; H includes it)
  Vec3 tau = {}, H_twin = {};  // transmittance, and what the other side receives (it passes τ H_twin through)
};
void add_to_audit(EnergyAudit& audit, const AuditElement& e);

// report.json's "energy_audit": the terms above (W, per channel), the relative imbalance, and whether
// it is within `bound` ("balanced"; 1e-4: what the stability suite holds closed scenes to with the
// classic method; open scenes and the hierarchical method's one-way links miss it, see numerics.md).
nlohmann::json audit_json(const EnergyAudit& audit, double bound = 1e-4);

}  // namespace walkrad
