#include "walkrad/pipeline/energy_audit.h"

#include <algorithm>
#include <cmath>

#include "walkrad/pipeline/link_transport.h"
#include "walkrad/pipeline/transmission.h"

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

namespace {

// The hierarchy's transfer as the solver runs it: irradiance gathered from what sources send (Bt), and
// what escapes counted where it leaves, per leaf: B A (1 − the fraction its links and its ancestors'
// carry away, times its send factor), so that the balance closes whatever the links' distribution.
void audit_node(const Hierarchy& h, uint32_t i, Vec3 down, double carried, const std::vector<double>& sent,
                const std::vector<uint32_t>* twins, EnergyAudit& audit) {
  const HNode& n = h[i];
  for (const Link& l : n.links) down += h[l.source].Bt * l.F;
  carried += sent[i];
  if (n.child_count == 0) {
    if (n.cluster) return;
    AuditElement e{n.area, n.rho, n.emission, n.B, down * n.receive + n.D, carried * n.send, n.D};
    if (twins && (*twins)[n.polygon] != kNoTwin) {  // what passes through from the other side
      e.tau = h.scene().materials[h.scene().polygons[n.polygon].material].transmittance;
      e.H_twin = twin_received(h, n, (*twins)[n.polygon]);
    }
    add_to_audit(audit, e);
    return;
  }
  for (uint32_t k = 0; k < n.child_count; ++k) audit_node(h, h.child(n, k), down, carried, sent, twins, audit);
}

}  // namespace

EnergyAudit audit_hierarchy(const Hierarchy& h, const std::vector<uint32_t>* twins) {
  EnergyAudit audit;
  // Σ F A_receiver ā_receiver / A_source over links from the node (ā: the receiver's mean receive factor).
  std::vector<double> sent(h.nodes().size(), 0.0);
  const std::vector<double> receive = mean_receive(h);
  for (size_t k = 0; k < h.nodes().size(); ++k)
    for (const Link& l : h.nodes()[k].links) sent[l.source] += l.F * h.nodes()[k].area * receive[k] / h[l.source].area;
  if (!h.nodes().empty()) audit_node(h, h.root(), Vec3{}, 0.0, sent, twins, audit);
  return audit;
}

nlohmann::json audit_json(const EnergyAudit& a, double bound) {
  auto v = [](const Vec3& x) { return nlohmann::json::array({x.x, x.y, x.z}); };
  return {{"emitted_w", v(a.emitted)},         {"absorbed_w", v(a.absorbed)},   {"residual_w", v(a.residual())},
          {"escaped_w", v(a.escaped)},         {"unconverged_w", v(a.unconverged)},
          {"imbalance", a.imbalance()},        {"bound", bound},
          {"balanced", a.imbalance() <= bound}};
}

}  // namespace walkrad
