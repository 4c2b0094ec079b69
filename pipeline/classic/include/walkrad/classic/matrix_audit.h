// The energy audit (walkrad/core/energy_audit.h) of the classic method's solution: every element of the
// full form factor matrix, its irradiance gathered afresh from the solution along its row.
#pragma once

#include <vector>

#include "walkrad/classic/form_factor_matrix.h"
#include "walkrad/core/energy_audit.h"

namespace walkrad {

// The classic method: elements of a full form factor matrix.
EnergyAudit audit_matrix(const FormFactorMatrix& f, const std::vector<double>& area, const std::vector<Vec3>& reflectance,
                         const std::vector<Vec3>& emission, const std::vector<Vec3>& radiosity);

}  // namespace walkrad
