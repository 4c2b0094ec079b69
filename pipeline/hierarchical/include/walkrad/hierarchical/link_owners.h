// Links divided among ranks (see docs/scaling.md): under mpirun, with Jacobi sweeps, the links
// whose receiver is an element of input polygon p live only on rank owner(p); cluster receivers'
// links, a few per cent of them, live on every rank. Everything else (the nodes, their radiosity and
// importance, the scene) is on every rank. A step that reads links runs on the rank that holds them
// and sends what it found per element node to the others (share_element_values); the sums every rank
// then makes run over nodes in the same order, so the result does not depend on the number of ranks.
// The division lasts to the end of the bake: the final gather's refinement, the vertices' radiosity
// and the energy audit read each element's links on its rank too (polygon_rank).
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/core/ranks.h"
#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad {

// Polygon p, the k-th in the cluster tree's order, to rank k mod ranks: neighbours alternate, so the
// few rooms a walkthrough looks into (most of the links) fall evenly on every rank.
LinkOwners divide_polygons(const ClusterTree& tree, int ranks, int me);

// The polygons dealt again by the links they hold now (each rank's counted and summed over the ranks,
// a polygon's cost its links + 1): from the rank holding the most to the one holding the least, the
// heaviest polygon that fits in half the gap, until every rank is within 2% of the mean; the links of
// the polygons that move sent to their new ranks. The deal depends only on the counts, the same on every
// rank, and no result depends on the deal. A collective call.
void rebalance_links(Hierarchy& h);

// The bytes this rank's links take (their lists' capacities): report.json's link_mb_peak, noted during
// the solve and again after the output stage, which reads the links where they are and adds none.
uint64_t link_bytes(const Hierarchy& h);

// Whether this rank holds node i's links (a cluster's: every rank).
inline bool holds_links(const Hierarchy& h, uint32_t i) {
  const HNode& n = h[i];
  return n.cluster || h.owners().holds_polygon(n.polygon);
}

// The rank that holds the links of the elements of input polygon p (0 when they are not divided):
// what reads those links (the final gather's candidates, the vertices' LeafRadiosity) runs there.
inline int polygon_rank(const Hierarchy& h, uint32_t polygon) {
  const LinkOwners& o = h.owners();
  return o.divided() ? int(o.rank[polygon]) : 0;
}

// Whether this rank adds node i's links to a total over the ranks, so that each link counts once: its
// own receivers' links, and the clusters' (on every rank) on rank 0 alone.
inline bool counts_links(const Hierarchy& h, uint32_t i) {
  const LinkOwners& o = h.owners();
  return h[i].cluster ? !o.divided() || o.me == 0 : o.holds_polygon(h[i].polygon);
}

// For every element node i, the value its polygon's rank computed (get(i) there) is given to the others
// (set(i, value) here). A collective call; nothing happens when the links are not divided.
template <class T, class Get, class Set>
void share_element_values(const Hierarchy& h, Get get, Set set) {
  const LinkOwners& o = h.owners();
  if (!o.divided()) return;
  share_owned<T>(
      h.nodes().size(), [&](size_t i) { const HNode& n = h[uint32_t(i)]; return n.cluster ? -1 : polygon_rank(h, n.polygon); },
      [&](size_t i) { return get(uint32_t(i)); }, [&](size_t i, const T& v) { set(uint32_t(i), v); });
}

// The same for a value per node kept in a vector.
template <class T>
void share_element_values(const Hierarchy& h, std::vector<T>& by_node) {
  share_element_values<T>(h, [&](uint32_t i) { return by_node[i]; }, [&](uint32_t i, const T& v) { by_node[i] = v; });
}

}  // namespace walkrad
