// A cluster's radiosity by direction (non-isotropic clusters: Sillion, Drettakis & Soler, "A clustering
// algorithm for radiance calculation in general environments", EGWR 1995). A cluster link's form factor
// counts only the surfaces that face the receiver (each sample's own cosine), so the radiosity it
// carries is theirs, weighed by the area each presents: Σ A_k max(0, n_k·u) B_k / Σ A_k max(0, n_k·u),
// not the cluster's area mean: a desk under a lamp shade, facing its white lining, was lit by the lining
// averaged with the shade's dark outside (MGF office3, 20-27% dark: docs/accuracy.md). The six axis
// ways bound the cost: Σ A_k max(0, ±n_k·e_a) B_k per cluster, each way weighed by max(0, ±u_a) (as
// HNode::facing holds the areas alone).
#pragma once

#include <array>
#include <vector>

#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad {

// Per node: for a cluster, Σ over its element roots of facing[a] × value (value: by node, the area
// mean of each element root's leaves); zero for elements.
std::vector<std::array<Vec3, 6>> facing_radiosity(const Hierarchy& h, const std::vector<Vec3>& value);

// What cluster n sends towards unit direction u (from n to the receiver): its surfaces' radiosity
// weighed by the area each presents to u; mean where none faces u (or n is an element).
Vec3 radiosity_towards(const HNode& n, const std::array<Vec3, 6>& facing_radiosity, const Vec3& u, const Vec3& mean);

}  // namespace walkrad
