// What holds of a hierarchy between the solver's rounds (walkrad/core/invariant.h): its tree's shape,
// its nodes' areas, its links' ranges and values. Checked after every round in debug and sanitizer
// builds; the tests call it in any build.
#pragma once

#include <string>

#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad {

// The first fault found, "" when there is none:
// - tree shape: every parent numbered before its children, each child's parent its parent, an
//   element's children the four quadrants of its own polygon, one level deeper;
// - areas: an element's children's areas sum to its own, a cluster's area is its children's sum
//   (relative 1e-9: split_element's quadrants partition it exactly, up to rounding);
// - links: every source a node, F, σ and the shares finite, F and σ not negative;
// - radiosity: every node's B finite.
std::string hierarchy_fault(const Hierarchy& h);

}  // namespace walkrad
