#include "walkrad/hierarchical/hierarchy_invariants.h"

#include <cmath>
#include <string>

namespace walkrad {

namespace {

std::string at(uint32_t i, const std::string& what) { return "node " + std::to_string(i) + ": " + what; }

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

std::string hierarchy_fault(const Hierarchy& h) {
  const size_t n = h.nodes().size();
  for (uint32_t i = 0; i < n; ++i) {
    const HNode& node = h[i];
    if (node.parent >= 0 && uint32_t(node.parent) >= i) return at(i, "its parent " + std::to_string(node.parent) + " comes after it");
    if (!node.cluster && node.child_count != 0 && node.child_count != 4)
      return at(i, "an element with " + std::to_string(node.child_count) + " children (0 or 4)");
    double children_area = 0;
    for (uint32_t k = 0; k < node.child_count; ++k) {
      const uint32_t c = h.child(node, k);
      if (c >= n) return at(i, "child " + std::to_string(c) + " out of range");
      const HNode& child = h[c];
      if (child.parent != int32_t(i)) return at(i, "child " + std::to_string(c) + " names parent " + std::to_string(child.parent));
      if (!node.cluster && (child.cluster || child.polygon != node.polygon || child.depth != node.depth + 1))
        return at(i, "child " + std::to_string(c) + " is not a quadrant of its polygon one level deeper");
      children_area += child.area;
    }
    if (node.child_count && std::fabs(children_area - node.area) > 1e-9 * node.area)
      return at(i, "area " + std::to_string(node.area) + " against its children's " + std::to_string(children_area));
    if (!finite(node.B)) return at(i, "radiosity not finite");
    for (const Link& l : node.links) {
      if (l.source >= n) return at(i, "a link from node " + std::to_string(l.source) + ", out of range");
      if (!std::isfinite(l.F) || l.F < 0 || !std::isfinite(l.sigma) || l.sigma < 0)
        return at(i, "the link from node " + std::to_string(l.source) + " has F " + std::to_string(l.F) + ", sigma " +
                         std::to_string(l.sigma));
      for (float s : l.share)
        if (!std::isfinite(s)) return at(i, "the link from node " + std::to_string(l.source) + " has a share not finite");
    }
  }
  return "";
}

}  // namespace walkrad
