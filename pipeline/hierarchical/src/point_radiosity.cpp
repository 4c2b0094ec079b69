#include "walkrad/hierarchical/point_radiosity.h"

#include "walkrad/formfactor/form_factor.h"
#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/hierarchical/directional_irradiance.h"
#include "walkrad/hierarchical/link_transport.h"

namespace walkrad {

namespace {

// Centre distances below this many times the two radii count as near.
constexpr double kNear = 3.0;

}  // namespace

ClusterGather::ClusterGather(const Hierarchy& h, bool indirect, const std::vector<PunctualLight>* lights, const RayScene* rays)
    : h_(h), indirect_(indirect), lights_(lights && !lights->empty() ? lights : nullptr), rays_(rays),
      H_(h.scene().polygons.size()), row_(h.scene().polygons.size(), 0.0) {
  // Down the cluster tree, each cluster's links added to its parent's, by direction.
  std::vector<DirectionalIrradiance> cube;
  std::vector<uint32_t> slot(h.nodes().size(), UINT32_MAX);
  for (uint32_t k = 0; k < h.nodes().size(); ++k) {  // parents first
    const HNode& n = h[k];
    const int32_t parent = n.parent;
    if (n.cluster) {
      slot[k] = uint32_t(cube.size());
      cube.push_back(parent >= 0 ? cube[slot[size_t(parent)]] : DirectionalIrradiance{});
      for (const Link& l : n.links) {
        const HNode& s = h[l.source];
        cube.back().add(n, link_direction(n, s), l.F, indirect ? s.Bt : s.emission);
      }
    } else if (n.depth == 0 && parent >= 0) {
      const DirectionalIrradiance& c = cube[slot[size_t(parent)]];
      H_[n.polygon] = c.at(n.normal);
      row_[n.polygon] = c.row(n.normal);
    }
  }
}

LeafRadiosity::LeafRadiosity(const ClusterGather& clusters, uint32_t leaf, bool transmitting)
    : clusters_(clusters), h_(clusters.hierarchy()), leaf_(leaf), indirect_(clusters.indirect()),
      flat_(h_[leaf].cluster || transmitting) {
  if (flat_) return;
  const Hierarchy& h = h_;
  const bool indirect = indirect_;
  const HNode& n = h[leaf];
  quadrants_ = split_element(n.shape);
  H_.fill(clusters.H(n.polygon));
  row_.fill(clusters.row(n.polygon));
  uint32_t below = leaf;  // the child of a on the way to the leaf: the element chain only
  for (int32_t a = int32_t(leaf); a >= 0 && !h[uint32_t(a)].cluster; below = uint32_t(a), a = h[uint32_t(a)].parent) {
    const HNode& r = h[uint32_t(a)];
    const bool own = uint32_t(a) == leaf;
    const uint32_t slot = own ? 0 : child_slot(h, below);
    for (const Link& l : r.links) {
      const HNode& s = h[l.source];
      const Vec3 sent = indirect ? s.Bt : s.emission;
      // A source element near the receiver: the point's own form factor (the kernel changes within a
      // share's quadrant there; farther, the shares say enough).
      if (!s.cluster && l.open > 0 && length(s.center - r.center) < kNear * (r.radius + s.radius)) {
        near_.push_back({l.source, l.F / double(l.open)});
        continue;
      }
      // As the solve pushes it: by the part's share (the leaf's own links by the quadrant the point
      // falls in).
      for (uint32_t q = 0; q < 4; ++q) {
        const double f = l.F * double(l.share[own ? q : slot]);
        H_[q] += sent * f;
        row_[q] += f;
      }
    }
  }
}

Vec3 LeafRadiosity::at(const Vec3& x) const {
  const HNode& n = h_[leaf_];
  if (flat_) return n.B;
  const uint32_t q = quadrant_of(quadrants_, n.normal, x);
  Vec3 H = H_[q];
  double row = row_[q];
  for (const Near& s : near_) {
    const HNode& src = h_[s.source];
    const double f = dot(x - src.shape.v[0], src.normal) > 0 ? point_to_polygon(x, n.normal, src.shape) * s.visible : 0.0;
    H += (indirect_ ? src.Bt : src.emission) * f;
    row += f;
  }
  uint64_t rays = 0;
  const Vec3 D = clusters_.lights() ? point_irradiance(x, n.normal, *clusters_.lights(), clusters_.rays(), rays) : n.D;
  return n.emission + mul(n.rho, leaf_irradiance(n, H, row) + D);
}

}  // namespace walkrad
