// Passes over a hierarchy in parallel that give the bits of a serial pass: each node is worked out
// from its children (bottom up) or from its parent (top down) by the same arithmetic in the same
// order whichever thread takes it; only the order between independent subtrees changes. The input
// polygons' element trees are independent of one another; a cluster's subtrees go to other threads
// where it holds kParallelPolygons input polygons or more. (Serial, the aggregation correction's
// passes over the 150-room level's nodes take 2 s a call, 16 calls a solve.)
#pragma once

#include <cstdint>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad {

constexpr uint32_t kParallelPolygons = 4096;

// f(k) for `cluster` and every cluster below it, each after the clusters among its children.
template <class F>
void clusters_bottom_up(const Hierarchy& h, uint32_t cluster, const F& f) {
  const HNode& n = h[cluster];
  auto below = [&](uint32_t c) {
    const uint32_t k = h.child(n, c);
    if (h[k].cluster) clusters_bottom_up(h, k, f);
  };
  if (h.polygon_count(n) >= kParallelPolygons)
    tbb::parallel_for(uint32_t(0), n.child_count, below);
  else
    for (uint32_t c = 0; c < n.child_count; ++c) below(c);
  f(cluster);
}

// state = f(k, above) for `cluster` and every cluster below it, `above` its parent's state (the
// caller's for `cluster`); f also does what the cluster's element roots take from it.
template <class State, class F>
void clusters_top_down(const Hierarchy& h, uint32_t cluster, const State& above, const F& f) {
  const State mine = f(cluster, above);
  const HNode& n = h[cluster];
  auto below = [&](uint32_t c) {
    const uint32_t k = h.child(n, c);
    if (h[k].cluster) clusters_top_down(h, k, mine, f);
  };
  if (h.polygon_count(n) >= kParallelPolygons)
    tbb::parallel_for(uint32_t(0), n.child_count, below);
  else
    for (uint32_t c = 0; c < n.child_count; ++c) below(c);
}

namespace walk_detail {
template <class F>
void element_post_order(const Hierarchy& h, uint32_t k, const F& f) {
  const HNode& n = h[k];
  for (uint32_t c = 0; c < n.child_count; ++c) element_post_order(h, h.child(n, c), f);
  f(k);
}
}  // namespace walk_detail

// f(k) for every element, each after its children: the input polygons' trees in parallel.
template <class F>
void elements_bottom_up(const Hierarchy& h, const F& f) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, h.scene().polygons.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t p = r.begin(); p != r.end(); ++p) {
      const uint32_t root = h.polygon_root(uint32_t(p));
      if (root != UINT32_MAX) walk_detail::element_post_order(h, root, f);
    }
  });
}

// f(k) for every node, each after its children: the elements, then the clusters.
template <class F>
void nodes_bottom_up(const Hierarchy& h, const F& f) {
  if (h.nodes().empty()) return;
  elements_bottom_up(h, f);
  if (h[h.root()].cluster) clusters_bottom_up(h, h.root(), f);
}

}  // namespace walkrad
