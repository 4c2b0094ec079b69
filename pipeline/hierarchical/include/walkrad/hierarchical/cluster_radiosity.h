// A cluster's radiosity by direction (non-isotropic clusters: Sillion, Drettakis & Soler, "A clustering
// algorithm for radiance calculation in general environments", EGWR 1995). A cluster link's form factor
// counts only the surfaces that face the receiver (each sample's own cosine), so the radiosity it
// carries is theirs, weighed by the area each presents: Σ A_k max(0, n_k·u) B_k / Σ A_k max(0, n_k·u),
// not the cluster's area mean: by the area mean, a desk under a lamp shade, facing its white lining, is
// lit by the lining averaged with the shade's dark outside (MGF office3: 20-27% dark). The six axis
// ways bound the cost: Σ A_k max(0, ±n_k·e_a) B_k per cluster, each way weighed by max(0, ±u_a) (as
// HNode::facing holds the areas alone).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/hierarchical/hierarchy_walk.h"

namespace walkrad {

// One cluster's sum from its children, the last first: a child cluster's own sums (facing[its tree_node]), an
// element root's facing areas × value(root). A Gauss-Seidel sweep takes it again for a cluster whose
// surfaces it has just updated (solve_sweep.cpp).
template <class Facing, class Value>
std::array<Vec3, 6> facing_from_children(const Hierarchy& h, uint32_t cluster, const Facing& facing, Value value) {
  std::array<Vec3, 6> out{};
  const HNode& n = h[cluster];
  for (uint32_t k = n.child_count; k-- > 0;) {
    const uint32_t c = h.child(n, k);
    const HNode& child = h[c];
    if (child.cluster) {
      for (size_t a = 0; a < 6; ++a) out[a] += facing[child.tree_node][a];
    } else {  // an element root: its leaves share its normal
      const Vec3 v = value(c);
      for (size_t a = 0; a < 6; ++a) out[a] += v * double(child.facing[a]);
    }
  }
  return out;
}

// By cluster (HNode::tree_node, Hierarchy::cluster_count()): Σ over its element roots of facing[a] ×
// value(root), value(k) node k's radiosity (an element root's: its leaves' area mean). Into `out`, whose
// memory is kept: a sweep takes them again every time (fresh pages are a fault each).
template <class Value, class Facing>  // Facing: a vector of std::array<Vec3, 6>, of any allocator
void facing_radiosity(const Hierarchy& h, Value value, Facing& out) {
  out.resize(h.cluster_count());  // every entry is set below
  if (h.nodes().empty()) return;
  // Each cluster after its children (hierarchy_walk.h: subtrees in parallel, the same bits).
  clusters_bottom_up(h, h.root(), [&](uint32_t k) { out[h[k].tree_node] = facing_from_children(h, k, out, value); });
}

template <class Value>
std::vector<std::array<Vec3, 6>> facing_radiosity(const Hierarchy& h, Value value) {
  std::vector<std::array<Vec3, 6>> out;
  facing_radiosity(h, value, out);
  return out;
}

// What cluster n sends towards unit direction u (from n to the receiver): its surfaces' radiosity
// weighed by the area each presents to u; mean where none faces u (or n is an element).
Vec3 radiosity_towards(const HNode& n, const std::array<Vec3, 6>& facing_radiosity, const Vec3& u, const Vec3& mean);

// What link l takes from its source towards a receiver centred at `at`: each part (its source's
// children by Link::seen, else the source whole) that is a cluster by direction from its own centre
// (facing: facing_radiosity's; empty: none), the rest what sent(node) gives. The solve's gather, the
// transport walk and the mesh's readings must take the same: a gather and a transport that differed
// made the aggregation correction fight the sweeps.
template <class Sent>
Vec3 link_radiosity_towards(const Hierarchy& h, const Link& l, const Vec3& at, const std::vector<std::array<Vec3, 6>>& facing,
                            Sent sent) {
  if (!has_seen(l) && !h[l.source].cluster) return sent(l.source);  // most links, every sweep: the plain read
  Vec3 out;
  for_each_part(h, l, [&](uint32_t node, double w) {
    const HNode& p = h[node];
    out += (p.cluster && p.tree_node < facing.size() ? radiosity_towards(p, facing[p.tree_node], normalize(at - p.center), sent(node))
                                                     : sent(node)) *
           w;
  });
  return out;
}

}  // namespace walkrad
