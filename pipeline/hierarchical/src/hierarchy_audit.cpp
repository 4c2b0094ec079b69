#include "walkrad/hierarchical/hierarchy_audit.h"

#include "walkrad/hierarchical/link_transport.h"
#include "walkrad/hierarchical/transmission.h"

namespace walkrad {

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

}  // namespace walkrad
