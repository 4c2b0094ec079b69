// Links divided among ranks (issue 28, docs/scaling.md): under mpirun, with Jacobi sweeps, the links
// whose receiver is an element of input polygon p live only on rank owner(p); cluster receivers'
// links, a few per cent of them, live on every rank. Everything else (the nodes, their radiosity and
// importance, the scene) is on every rank. A step that reads links runs on the rank that holds them
// and sends what it found per element node to the others (share_element_values); the sums every rank
// then makes run over nodes in the same order, so the result does not depend on the number of ranks.
#pragma once

#include <cstdint>
#include <cstring>
#include <type_traits>
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

// Every rank given every link, and the division ended: what follows the solve (the final gather, the
// mesh) reads an element's links wherever it is. A collective call, a piece of the nodes at a time.
void join_links(Hierarchy& h);

// Whether this rank holds node i's links (a cluster's: every rank).
inline bool holds_links(const Hierarchy& h, uint32_t i) {
  const HNode& n = h[i];
  return n.cluster || h.owners().holds_polygon(n.polygon);
}

// For every element node i, the value its polygon's rank computed (get(i) there) is given to the others
// (set(i, value) here). A collective call; nothing happens when the links are not divided.
template <class T, class Get, class Set>
void share_element_values(const Hierarchy& h, Get get, Set set) {
  const size_t count = h.nodes().size();
  static_assert(std::is_trivially_copyable_v<T>);
  const LinkOwners& o = h.owners();
  if (!o.divided()) return;
  std::vector<uint8_t> mine;
  std::vector<size_t> per_rank(size_t(ranks().size), 0);
  for (uint32_t i = 0; i < count; ++i) {
    const HNode& n = h[i];
    if (n.cluster) continue;
    const uint16_t r = o.rank[n.polygon];
    ++per_rank[r];
    if (r != o.me) continue;
    const T v = get(i);
    const size_t at = mine.size();
    mine.resize(at + sizeof(T));
    std::memcpy(mine.data() + at, &v, sizeof(T));
  }
  const std::vector<uint8_t> all = all_gather(mine);
  std::vector<size_t> offset(per_rank.size(), 0);
  for (size_t r = 1; r < offset.size(); ++r) offset[r] = offset[r - 1] + per_rank[r - 1] * sizeof(T);
  for (uint32_t i = 0; i < count; ++i) {
    const HNode& n = h[i];
    if (n.cluster) continue;
    const uint16_t r = o.rank[n.polygon];
    size_t& at = offset[r];
    if (r != o.me) {
      T v;
      std::memcpy(&v, all.data() + at, sizeof(T));
      set(i, v);
    }
    at += sizeof(T);
  }
}

// The same for a value per node kept in a vector.
template <class T>
void share_element_values(const Hierarchy& h, std::vector<T>& by_node) {
  share_element_values<T>(h, [&](uint32_t i) { return by_node[i]; }, [&](uint32_t i, const T& v) { by_node[i] = v; });
}

}  // namespace walkrad
