// How a cluster passes what it receives on to its surfaces (algorithms.md §7). A cluster link's form
// factor is the mean over all the cluster's surfaces, each with its own cosine; pushed down uniformly,
// the books' spines facing a room and their backs facing the wall get the same irradiance, and a
// bookcase's spines came out at a third of their light. Here each link's transfer is kept by the
// direction it comes from, along the six half-axes (an "ambient cube"), and a surface of normal n takes
// Σ_a |n_a| × the component on its side of axis a. Scaled by the cluster's mean cosine towards the
// source (from HNode::facing), the surfaces' shares add up to the link's power exactly: A F B.
#pragma once

#include <array>

#include "walkrad/hierarchical/hierarchy.h"

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

}  // namespace walkrad
