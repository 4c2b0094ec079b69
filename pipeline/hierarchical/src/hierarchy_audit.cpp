#include "walkrad/hierarchical/hierarchy_audit.h"

#include "walkrad/hierarchical/directional_irradiance.h"
#include "walkrad/hierarchical/link_owners.h"
#include "walkrad/hierarchical/link_transport.h"
#include "walkrad/hierarchical/transmission.h"

namespace walkrad {

namespace {

// What a link takes from its source's Bt (Link::seen).
Vec3 link_bt(const Hierarchy& h, const Link& l) {
  Vec3 b;
  for_each_part(h, l, [&](uint32_t node, double w) { b += h[node].Bt * w; });
  return b;
}

// The hierarchy's transfer as the solver runs it: irradiance gathered from what sources send (Bt), and
// what escapes counted where it leaves, per leaf: B A (1 − the fraction its links and its ancestors'
// carry away, times its send factor), so that the balance closes whatever the links' distribution.
void audit_node(const Hierarchy& h, uint32_t i, Vec3 down, DirectionalIrradiance cube, double carried,
                const std::vector<double>& sent, const std::vector<uint32_t>* twins, EnergyAudit& audit) {
  const HNode& n = h[i];
  if (!n.cluster && !h.owners().holds_polygon(n.polygon)) return;  // its links' rank counts it
  carried += sent[i];
  if (n.cluster)
    for (const Link& l : n.links) cube.add(n, link_direction(n, h[l.source]), l.F, link_bt(h, l));
  if (n.child_count == 0) {
    for (const Link& l : n.links) down += link_bt(h, l) * l.F;
    if (n.cluster) return;
    AuditElement e{n.area, n.rho, n.emission, n.B, down * n.receive + n.D, carried * n.send, n.D};
    if (twins && (*twins)[n.polygon] != kNoTwin) {  // what passes through from the other side
      e.tau = material_transmittance(h, n);
      e.H_twin = twin_received(h, n, (*twins)[n.polygon]);
    }
    add_to_audit(audit, e);
    return;
  }
  for (uint32_t k = 0; k < n.child_count; ++k) {  // as the solve pushes (solve_sweep.cpp)
    const HNode& child = h[h.child(n, k)];
    Vec3 pushed = down;
    if (n.cluster && !child.cluster) pushed += cube.at(child.normal);
    if (!n.cluster && k < 4)
      for (const Link& l : n.links) pushed += link_bt(h, l) * (l.F * double(l.share[k]));
    audit_node(h, h.child(n, k), pushed, child.cluster ? cube : DirectionalIrradiance{}, carried, sent, twins, audit);
  }
}

}  // namespace

EnergyAudit audit_hierarchy(const Hierarchy& h, const std::vector<uint32_t>* twins) {
  EnergyAudit audit;
  // Σ F A_receiver ā_receiver / A_source over links from the node (ā: the receiver's mean receive factor).
  std::vector<double> sent(h.nodes().size(), 0.0);
  const std::vector<double> receive = mean_receive(h);
  // Links divided among ranks (link_owners.h): each counted on one rank, the ranks' sums added up.
  const LinkOwners& owners = h.owners();
  for (size_t k = 0; k < h.nodes().size(); ++k) {
    const HNode& p = h.nodes()[k];
    if (!counts_links(h, uint32_t(k))) continue;
    for (const Link& l : p.links) {
      // What the receiver takes: an element's children's areas by their shares and receive factors
      // (a cluster's by direction, taken as even).
      double taken = p.area * receive[k];
      if (p.child_count && !p.cluster) {
        taken = 0;
        for (uint32_t c = 0; c < p.child_count && c < 4; ++c)
          taken += h[h.child(p, c)].area * double(l.share[c]) * receive[h.child(p, c)];
      }
      for_each_part(h, l, [&](uint32_t node, double w) { sent[node] += l.F * taken * w / h[node].area; });  // Link::seen
    }
  }
  if (owners.divided()) all_sum(sent.data(), sent.size());
  if (!h.nodes().empty()) audit_node(h, h.root(), Vec3{}, DirectionalIrradiance{}, 0.0, sent, twins, audit);
  if (owners.divided()) {
    Vec3* terms[] = {&audit.emitted, &audit.absorbed, &audit.escaped, &audit.unconverged};
    double sum[12];
    for (int t = 0; t < 4; ++t) {
      sum[3 * t] = terms[t]->x;
      sum[3 * t + 1] = terms[t]->y;
      sum[3 * t + 2] = terms[t]->z;
    }
    all_sum(sum, 12);
    for (int t = 0; t < 4; ++t) *terms[t] = {sum[3 * t], sum[3 * t + 1], sum[3 * t + 2]};
  }
  return audit;
}

}  // namespace walkrad
