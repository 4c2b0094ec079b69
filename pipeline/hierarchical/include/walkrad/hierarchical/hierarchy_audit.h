// The energy audit (walkrad/core/energy_audit.h) of the hierarchical method's solution.
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/core/energy_audit.h"
#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad {

// The hierarchical method: the leaves of the hierarchy, each receiving along its own links and its
// ancestors' (irradiance and row sums pushed down as the solver does, without its row-sum clamp).
// twins: transmission twins per polygon (walkrad/scene/transmission_twins.h), or nullptr.
EnergyAudit audit_hierarchy(const Hierarchy& h, const std::vector<uint32_t>* twins = nullptr);

}  // namespace walkrad
