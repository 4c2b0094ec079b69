#include "walkrad/core/energy_audit.h"

#include <algorithm>
#include <cmath>

namespace walkrad {

double EnergyAudit::imbalance() const {
  const Vec3 miss = emitted - absorbed - residual();
  double worst = 0;
  for (int c = 0; c < 3; ++c)
    if (emitted[c] > 0) worst = std::max(worst, std::fabs(miss[c]) / emitted[c]);
  return worst;
}

void add_to_audit(EnergyAudit& audit, const AuditElement& e) {
  audit.emitted += (e.emission + e.direct) * e.area;
  audit.absorbed += mul(Vec3(1, 1, 1) - e.rho - e.tau, e.H) * e.area;
  audit.escaped += e.B * (e.area * (1.0 - e.row_sum));
  audit.unconverged += (e.emission + mul(e.rho, e.H) + mul(e.tau, e.H_twin) - e.B) * e.area;
}

nlohmann::json audit_json(const EnergyAudit& a, double bound) {
  auto v = [](const Vec3& x) { return nlohmann::json::array({x.x, x.y, x.z}); };
  return {{"emitted_w", v(a.emitted)},         {"absorbed_w", v(a.absorbed)},   {"residual_w", v(a.residual())},
          {"escaped_w", v(a.escaped)},         {"unconverged_w", v(a.unconverged)},
          {"imbalance", a.imbalance()},        {"bound", bound},
          {"balanced", a.imbalance() <= bound}};
}

}  // namespace walkrad
