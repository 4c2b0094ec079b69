#include "walkrad/classic/matrix_audit.h"

namespace walkrad {

EnergyAudit audit_matrix(const FormFactorMatrix& f, const std::vector<double>& area, const std::vector<Vec3>& reflectance,
                         const std::vector<Vec3>& emission, const std::vector<Vec3>& radiosity) {
  EnergyAudit audit;
  for (size_t i = 0; i < f.rows(); ++i) {
    AuditElement e{area[i], reflectance[i], emission[i], radiosity[i], {}, 0.0, {}};
    for (uint64_t k = f.row_start[i]; k < f.row_start[i + 1]; ++k) {
      e.H += radiosity[f.column[k]] * f.value[k];
      e.row_sum += f.value[k];
    }
    add_to_audit(audit, e);
  }
  return audit;
}

}  // namespace walkrad
