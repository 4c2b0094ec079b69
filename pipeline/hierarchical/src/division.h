// How the hierarchical solve is divided among ranks (link_owners.h, docs/scaling.md), handed to each
// of the solver's parts that acts on it: the refinement (a receiver's plan made by the rank holding its
// links, applied on every rank), the sweeps (a rank gathers its own receivers; importance shot in
// exact units) and the round's links (a rank evaluates its own receivers'). One process that holds
// every link divides nothing. Private to this stage.
#pragma once

#include <cstdint>

#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/hierarchical/link_owners.h"

namespace walkrad::hierarchical_detail {

struct Division {
  // Jacobi sweeps, no closure balance, no transmission (indivisible_because): the steps that read links
  // run as a divided solve runs them, whatever the rank count, so that its result is the same.
  bool divisible = false;
  // Divisible, over several ranks, no checkpoints (undivided_because): links divided among ranks.
  bool divided = false;

  // Whether this rank keeps the links of receiver i (always, unless divided).
  bool here(const Hierarchy& h, uint32_t i) const { return !divided || holds_links(h, i); }
};

}  // namespace walkrad::hierarchical_detail
