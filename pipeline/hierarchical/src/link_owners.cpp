#include "walkrad/hierarchical/link_owners.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <cstring>

namespace walkrad {

namespace {

// The links of the element nodes whose polygons move (send(node): from this rank; take(node): to it),
// a piece of the nodes at a time (all_gather takes at most 2 GB): each rank packs (node, count, links)
// for its nodes of the piece that move, freeing them, and every rank receives every pack and keeps
// what it takes.
template <class Send, class Take>
void move_links(Hierarchy& h, Send send, Take take) {
  constexpr size_t kPiece = size_t(1) << 15;
  for (size_t first = 0; first < h.nodes().size(); first += kPiece) {
    std::vector<uint8_t> mine;
    for (size_t i = first; i < std::min(h.nodes().size(), first + kPiece); ++i) {
      HNode& n = h[uint32_t(i)];
      if (n.cluster || n.links.empty() || !send(n)) continue;
      const uint32_t head[2] = {uint32_t(i), uint32_t(n.links.size())};
      const size_t at = mine.size(), bytes = n.links.size() * sizeof(Link);
      mine.resize(at + sizeof(head) + bytes);
      std::memcpy(mine.data() + at, head, sizeof(head));
      std::memcpy(mine.data() + at + sizeof(head), n.links.data(), bytes);
      std::vector<Link>().swap(n.links);
    }
    const std::vector<uint8_t> all = all_gather(mine);
    for (size_t at = 0; at < all.size();) {
      uint32_t head[2];
      std::memcpy(head, all.data() + at, sizeof(head));
      at += sizeof(head);
      HNode& n = h[head[0]];
      const size_t bytes = size_t(head[1]) * sizeof(Link);
      if (take(n)) {
        n.links.resize(head[1]);
        std::memcpy(n.links.data(), all.data() + at, bytes);
      }
      at += bytes;
    }
  }
}

}  // namespace

uint64_t link_bytes(const Hierarchy& h) {
  // A walk over every node (a whole pass over the hierarchy's memory, noted each round): in parallel,
  // an integer sum being the same in any order.
  const HNodes& nodes = h.nodes();
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, nodes.size(), 4096), uint64_t(0),
      [&](const tbb::blocked_range<size_t>& r, uint64_t bytes) {
        for (size_t k = r.begin(); k != r.end(); ++k) bytes += nodes[k].links.capacity() * sizeof(Link);
        return bytes;
      },
      [](uint64_t a, uint64_t b) { return a + b; });
}

LinkOwners divide_polygons(const ClusterTree& tree, int ranks, int me) {
  LinkOwners o;
  o.me = uint16_t(me);
  o.rank.assign(tree.polygons.size(), 0);
  for (size_t k = 0; k < tree.polygons.size(); ++k) o.rank[tree.polygons[k]] = uint16_t(k % size_t(ranks));
  return o;
}

void rebalance_links(Hierarchy& h) {
  LinkOwners& o = h.owners();
  if (!o.divided()) return;
  const size_t polygons = o.rank.size();
  std::vector<int64_t> cost(polygons, 0);
  for (const HNode& n : h.nodes())
    if (!n.cluster && o.holds_polygon(n.polygon)) cost[n.polygon] += int64_t(n.links.size());
  all_sum(cost.data(), cost.size());
  // Moves, from the rank holding the most to the rank holding the least (ties: the lower rank), the
  // heaviest polygon that fits in half the gap, until the ranks are within 2% of their mean: few
  // polygons move once the deal is even (a new deal each round moved most of the links every round).
  const size_t count = size_t(ranks().size);
  std::vector<uint16_t> next = o.rank;
  std::vector<int64_t> load(count, 0);
  std::vector<std::vector<std::pair<int64_t, uint32_t>>> held(count);  // (cost + 1, tree position), heaviest first
  const std::vector<uint32_t>& tree_order = h.tree().polygons;
  for (size_t k = 0; k < tree_order.size(); ++k) {
    const uint32_t p = tree_order[k];
    load[next[p]] += cost[p] + 1;
    held[next[p]].push_back({cost[p] + 1, uint32_t(k)});
  }
  auto heavier = [](const std::pair<int64_t, uint32_t>& a, const std::pair<int64_t, uint32_t>& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  };
  for (auto& list : held) std::sort(list.begin(), list.end(), heavier);
  int64_t total = 0;
  for (int64_t l : load) total += l;
  const int64_t slack = std::max<int64_t>(1, total / int64_t(count) / 50);
  std::vector<uint8_t> moved(tree_order.size(), 0);
  for (size_t step = 0; step < tree_order.size(); ++step) {
    const size_t heavy = size_t(std::max_element(load.begin(), load.end()) - load.begin());
    const size_t light = size_t(std::min_element(load.begin(), load.end()) - load.begin());
    const int64_t gap = load[heavy] - load[light];
    if (gap <= slack) break;
    std::vector<std::pair<int64_t, uint32_t>>& list = held[heavy];
    auto at = std::lower_bound(list.begin(), list.end(), gap / 2, [](const auto& e, int64_t v) { return e.first > v; });
    while (at != list.end() && moved[at->second]) ++at;
    if (at == list.end()) break;
    const auto [weight, position] = *at;
    moved[position] = 1;
    list.erase(at);
    const uint32_t p = tree_order[position];
    next[p] = uint16_t(light);
    load[heavy] -= weight;
    load[light] += weight;
    held[light].insert(std::lower_bound(held[light].begin(), held[light].end(), std::make_pair(weight, position), heavier),
                       {weight, position});
  }
  // The links that move, sent to their new ranks.
  move_links(h, [&](const HNode& n) { return o.rank[n.polygon] == o.me && next[n.polygon] != o.me; },
             [&](const HNode& n) { return next[n.polygon] == o.me; });
  o.rank = std::move(next);
}

}  // namespace walkrad
