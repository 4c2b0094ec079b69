#include "walkrad/visibility/shaft.h"
#include "walkrad/core/rounding.h"

#include <algorithm>

#include <cmath>

namespace walkrad {

Shaft::Shaft(const Bounds& a, const Bounds& b) {
  hull_ = a;
  hull_.extend(b);
  // For each pair of axes (k, l) and each corner direction (sk, sl) of the hull's cross-section: if
  // one box alone reaches the hull along k and the other alone along l, the hull's corner is
  // empty, and the plane through the two boxes' corner edges (parallel to the third axis) cuts it off.
  for (int k = 0; k < 3; ++k)
    for (int l = k + 1; l < 3; ++l)
      for (int sk = 0; sk < 2; ++sk)
        for (int sl = 0; sl < 2; ++sl) {
          auto extreme = [](const Bounds& box, int axis, int s) { return s ? box.hi[axis] : box.lo[axis]; };
          auto further = [](double x, double y, int s) { return s ? x > y : x < y; };
          const bool a_k = further(extreme(a, k, sk), extreme(b, k, sk), sk);
          const bool b_k = further(extreme(b, k, sk), extreme(a, k, sk), sk);
          const bool a_l = further(extreme(a, l, sl), extreme(b, l, sl), sl);
          const bool b_l = further(extreme(b, l, sl), extreme(a, l, sl), sl);
          if (!((a_k && b_l) || (b_k && a_l))) continue;
          // Corner points of each box in the (k, l) plane.
          const double ak = extreme(a, k, sk), al = extreme(a, l, sl), bk = extreme(b, k, sk), bl = extreme(b, l, sl);
          // Line through (ak, al) and (bk, bl); normal perpendicular, pointing to the (sk, sl) corner.
          double nk = -(bl - al), nl = bk - ak;
          const double sign_k = sk ? 1.0 : -1.0, sign_l = sl ? 1.0 : -1.0;
          if (nk * sign_k + nl * sign_l < 0) { nk = -nk; nl = -nl; }
          const double len = std::sqrt(nk * nk + nl * nl);
          if (len == 0) continue;
          Plane p;
          p.nk = nk / len;
          p.nl = nl / len;
          p.d = (p.nk * ak + p.nl * al);
          static constexpr double Vec3::*kAxis[3] = {&Vec3::x, &Vec3::y, &Vec3::z};
          p.k = kAxis[k];
          p.l = kAxis[l];
          p.inner_k = p.nk >= 0 ? &Bounds::lo : &Bounds::hi;
          p.outer_k = p.nk >= 0 ? &Bounds::hi : &Bounds::lo;
          p.inner_l = p.nl >= 0 ? &Bounds::lo : &Bounds::hi;
          p.outer_l = p.nl >= 0 ? &Bounds::hi : &Bounds::lo;
          plane_[planes_++] = p;
        }
  // Touching is not overlapping: a polygon that only touches the hull's boundary (the wall beside a
  // floor element) cannot block a segment between the two boxes' interiors, and ray end points are
  // offset off their surfaces into the hull. The margin absorbs rounding: 1e-9 of the hull's own size
  // plus rounding at its coordinates (rounding.h), never an absolute length (a margin of
  // 1e-9 × |coordinates| is 30% of a 2 mm scene placed 1e5 m away, and loses its occluders; see
  // docs/numerics.md).
  const double extent = std::max({hull_.hi.x - hull_.lo.x, hull_.hi.y - hull_.lo.y, hull_.hi.z - hull_.lo.z});
  const double margin = 1e-9 * extent + rounding_at(hull_.lo) + rounding_at(hull_.hi);
  for (int k = 0; k < 3; ++k) {
    inner_lo_[k] = hull_.lo[k] + margin;
    inner_hi_[k] = hull_.hi[k] - margin;
    flat_[k] = !(hull_.hi[k] - hull_.lo[k] > 2 * margin);
  }
  for (int i = 0; i < planes_; ++i) inner_d_[i] = plane_[i].d - margin;
}

bool Shaft::overlaps(const Bounds& box) const {
  for (int k = 0; k < 3; ++k)
    if (box.hi[k] <= inner_lo_[k] || box.lo[k] >= inner_hi_[k]) {
      // A flat hull (two coplanar elements) has zero thickness: only a box crossing its plane counts.
      if (!flat_[k] || box.hi[k] <= hull_.lo[k] || box.lo[k] >= hull_.hi[k]) return false;
    }
  for (int i = 0; i < planes_; ++i) {
    const Plane& p = plane_[i];
    // The box's corner furthest inside (most negative along n): outside if even it is not inside.
    if (p.nk * (box.*p.inner_k).*p.k + p.nl * (box.*p.inner_l).*p.l >= inner_d_[i]) return false;
  }
  return true;
}

bool Shaft::contains(const Bounds& box) const {
  for (int k = 0; k < 3; ++k)
    if (!(box.lo[k] > inner_lo_[k] && box.hi[k] < inner_hi_[k])) return false;  // a flat hull contains nothing
  for (int i = 0; i < planes_; ++i) {
    const Plane& p = plane_[i];
    // The box's corner furthest out along n: inside if even it is.
    if (!(p.nk * (box.*p.outer_k).*p.k + p.nl * (box.*p.outer_l).*p.l < inner_d_[i])) return false;
  }
  return true;
}

namespace {

// Depth-first from `start`, child 0 first: entries come out in tree order, each handed to emit, which
// returns false to stop the walk (then so does this). tags null: no volumes. compact (without tags):
// a node wholly inside the shaft is one entry.
template <class Emit>
bool descend(const ClusterTree& tree, const Shaft& shaft, int32_t start, uint32_t exclude_a, uint32_t exclude_b,
             const VolumeTags* tags, bool compact, Emit&& emit) {
  std::vector<int32_t> stack = {start};
  while (!stack.empty()) {
    const int32_t index = stack.back();
    const ClusterNode& node = tree.nodes[size_t(index)];
    stack.pop_back();
    if (!shaft.overlaps(node.bounds)) continue;
    if (compact && shaft.contains(node.bounds)) {
      if (!emit(uint32_t(index) | kWholeNode)) return false;
      continue;
    }
    if (tags && tags->node[size_t(index)] && tags->see_through(uint32_t(index) | kVolumeNode)) {
      if (!emit(uint32_t(index) | kVolumeNode)) return false;
      continue;
    }
    if (!node.leaf()) {
      stack.push_back(node.child[1]);
      stack.push_back(node.child[0]);
      continue;
    }
    for (uint32_t i = node.first; i < node.first + node.count; ++i) {
      const uint32_t p = tree.polygons[i];
      if (p == exclude_a || p == exclude_b || !shaft.overlaps(tree.polygon_bounds[p])) continue;
      if (!emit(tags && tags->polygon[p] && tags->see_through(p | kVolumePolygon) ? p | kVolumePolygon : p)) return false;
    }
  }
  return true;
}

void collect(const ClusterTree& tree, const Shaft& shaft, int32_t start, uint32_t exclude_a, uint32_t exclude_b,
             const VolumeTags* tags, std::vector<uint32_t>& out, bool compact = false) {
  descend(tree, shaft, start, exclude_a, exclude_b, tags, compact, [&](uint32_t entry) {
    out.push_back(entry);
    return true;
  });
}

// A parent's compact list filtered by a child's shaft, each entry handed to emit (false: stop).
template <class Emit>
void filter_compact(const ClusterTree& tree, const Shaft& shaft, const std::vector<uint32_t>& candidates, uint32_t exclude_a,
                    uint32_t exclude_b, Emit&& emit) {
  for (uint32_t c : candidates) {
    if (c & kWholeNode) {
      const uint32_t k = c & ~kWholeNode;
      if (shaft.contains(tree.nodes[k].bounds) ? !emit(c) : !descend(tree, shaft, int32_t(k), exclude_a, exclude_b, nullptr, true, emit))
        return;
    } else if (c != exclude_a && c != exclude_b && shaft.overlaps(tree.polygon_bounds[c]) && !emit(c)) {
      return;
    }
  }
}

bool under(const ClusterTree& tree, const ClusterNode& node, uint32_t polygon) {
  return polygon < tree.slot.size() && tree.slot[polygon] - node.first < node.count;
}

// The polygons one compact entry stands for, less the two ends' own.
size_t entry_count(const ClusterTree& tree, uint32_t entry, uint32_t exclude_a, uint32_t exclude_b) {
  if (!(entry & kWholeNode)) return 1;
  const ClusterNode& node = tree.nodes[entry & ~kWholeNode];
  return node.count - under(tree, node, exclude_a) - (exclude_b != exclude_a && under(tree, node, exclude_b));
}

}  // namespace

std::vector<uint32_t> compact_candidates(const ClusterTree& tree, const Shaft& shaft, uint32_t exclude_a, uint32_t exclude_b) {
  std::vector<uint32_t> out;
  if (!tree.nodes.empty()) collect(tree, shaft, 0, exclude_a, exclude_b, nullptr, out, true);
  return out;
}

std::vector<uint32_t> filter_compact_candidates(const ClusterTree& tree, const Shaft& shaft, const std::vector<uint32_t>& candidates,
                                                uint32_t exclude_a, uint32_t exclude_b) {
  std::vector<uint32_t> out;
  filter_compact(tree, shaft, candidates, exclude_a, exclude_b, [&](uint32_t entry) {
    out.push_back(entry);
    return true;
  });
  return out;
}

size_t candidate_count(const ClusterTree& tree, const std::vector<uint32_t>& candidates, uint32_t exclude_a, uint32_t exclude_b) {
  size_t n = 0;
  for (uint32_t c : candidates) n += entry_count(tree, c, exclude_a, exclude_b);
  return n;
}

size_t count_compact_candidates(const ClusterTree& tree, const Shaft& shaft, const std::vector<uint32_t>& candidates,
                                uint32_t exclude_a, uint32_t exclude_b, size_t limit) {
  size_t n = 0;
  if (limit == 0) return 0;
  filter_compact(tree, shaft, candidates, exclude_a, exclude_b, [&](uint32_t entry) {
    n += entry_count(tree, entry, exclude_a, exclude_b);
    return n < limit;
  });
  return std::min(n, limit);
}

std::vector<uint32_t> expand_candidates(const ClusterTree& tree, const std::vector<uint32_t>& candidates, uint32_t exclude_a,
                                        uint32_t exclude_b) {
  std::vector<uint32_t> out;
  for (uint32_t c : candidates) {
    if (!(c & kWholeNode)) {
      out.push_back(c);
      continue;
    }
    const ClusterNode& node = tree.nodes[c & ~kWholeNode];
    for (uint32_t i = node.first; i < node.first + node.count; ++i)
      if (tree.polygons[i] != exclude_a && tree.polygons[i] != exclude_b) out.push_back(tree.polygons[i]);
  }
  return out;
}

std::vector<uint32_t> shaft_candidates(const ClusterTree& tree, const Shaft& shaft, uint32_t exclude_a, uint32_t exclude_b) {
  std::vector<uint32_t> out;
  if (!tree.nodes.empty()) collect(tree, shaft, 0, exclude_a, exclude_b, nullptr, out);
  return out;
}

std::vector<uint32_t> shaft_candidates(const ClusterTree& tree, const Shaft& shaft, uint32_t exclude_a, uint32_t exclude_b,
                                       const VolumeTags& tags) {
  std::vector<uint32_t> out;
  if (!tree.nodes.empty()) collect(tree, shaft, 0, exclude_a, exclude_b, &tags, out);
  return out;
}

std::vector<uint32_t> filter_candidates(const ClusterTree& tree, const Shaft& shaft, const std::vector<uint32_t>& candidates,
                                        uint32_t exclude_a, uint32_t exclude_b) {
  std::vector<uint32_t> out;
  for (uint32_t p : candidates)
    if (p != exclude_a && p != exclude_b && shaft.overlaps(tree.polygon_bounds[p])) out.push_back(p);
  return out;
}

std::vector<uint32_t> filter_candidates(const ClusterTree& tree, const Shaft& shaft, const std::vector<uint32_t>& candidates,
                                        uint32_t exclude_a, uint32_t exclude_b, const VolumeTags& tags) {
  std::vector<uint32_t> out;
  for (uint32_t c : candidates) {
    if (c & kVolumeNode) {  // kept whole if the rule still holds for this link, else opened
      collect(tree, shaft, int32_t(c & ~kVolumeNode), exclude_a, exclude_b, &tags, out);
      continue;
    }
    const uint32_t p = c & ~kVolumePolygon;
    if (p == exclude_a || p == exclude_b || !shaft.overlaps(tree.polygon_bounds[p])) continue;
    out.push_back((c & kVolumePolygon) && tags.see_through(c) ? c : p);
  }
  return out;
}

}  // namespace walkrad
