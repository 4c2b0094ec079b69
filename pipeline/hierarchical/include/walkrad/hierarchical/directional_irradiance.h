// How a cluster passes what it receives on to its surfaces (algorithms.md §7). A cluster link's form
// factor is the mean over all the cluster's surfaces, each with its own cosine; pushed down uniformly,
// the books' spines facing a room and their backs facing the wall get the same irradiance, and a
// bookcase's spines came out at a third of their light. Here each link's transfer is kept by the
// direction it comes from, along the six half-axes (an "ambient cube"), and a surface of normal n takes
// Σ_a |n_a| × the component on its side of axis a. Scaled by the cluster's mean cosine towards the
// source (from HNode::facing), the surfaces' shares add up to the link's power exactly: A F B.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/hierarchical/hierarchy_walk.h"

namespace walkrad {

struct DirectionalIrradiance {
  std::array<Vec3, 6> H{};       // irradiance per unit cosine, +x −x +y −y +z −z
  std::array<double, 6> F{};     // form factor per unit cosine, the same way (row sums)

  // A transfer F·B arriving at the cluster from unit direction u (cluster to source).
  void add(const HNode& cluster, const Vec3& u, double form_factor, const Vec3& B);

  // What a surface of unit normal n receives: irradiance, and its form factor sum.
  Vec3 at(const Vec3& n) const;
  double row(const Vec3& n) const;

  DirectionalIrradiance& operator+=(const DirectionalIrradiance& o);
};

// The unit direction from a link's receiver to its source (centre to centre).
Vec3 link_direction(const HNode& receiver, const HNode& source);

// What the clusters' links deliver, N quantities at once, down the cluster tree: each cluster's cubes
// are its parent's plus its own links' in their order (value(link, cluster): the N radiosities the link
// brings), and take(root, cubes) hands them to each element root just below it. Subtrees in parallel
// (hierarchy_walk.h): the bits of a walk in node order. The solve's transport (link_transport.cpp) and
// the mesh's readings (point_radiosity.cpp) both take it so.
template <size_t N, class Value, class Take>
void gather_down_clusters(const Hierarchy& h, Value value, Take take) {
  using Cubes = std::array<DirectionalIrradiance, N>;
  if (h.nodes().empty()) return;
  clusters_top_down(h, h.root(), Cubes{}, [&](uint32_t k, const Cubes& above) {
    const HNode& n = h[k];
    Cubes mine = above;
    for (const Link& l : n.links) {
      if (!carries(l)) continue;
      const Vec3 u = link_direction(n, h[l.source]);
      const std::array<Vec3, N> v = value(l, n);
      for (size_t m = 0; m < N; ++m) mine[m].add(n, u, l.F, v[m]);
    }
    for (uint32_t c = 0; c < n.child_count; ++c)
      if (!h[h.child(n, c)].cluster) take(h.child(n, c), mine);
    return mine;
  });
}

}  // namespace walkrad
