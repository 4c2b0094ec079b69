// Refinement of the hierarchy's links (Hanrahan, Salzman & Aupperle 1991; clusters: Smits, Arvo &
// Greenberg 1994): where a link's oracle exceeds ε, split an end and recurse; shafts carry the
// candidate occluders down.
#include "solver.h"

#include <algorithm>
#include <cmath>

#include "walkrad/core/rounding.h"

namespace walkrad::hierarchical_detail {

namespace {

// Mean max(cos, 0) over random orientations: a cluster's mean projected area is A/4 (Sillion 1995).
// Used by the refinement oracle's estimate; link form factors use each surface's own cosine.
constexpr double kClusterCosine = 0.25;

// Distance between two boxes (0 when they overlap or touch).
double box_distance(const Bounds& a, const Bounds& b) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({0.0, b.lo[k] - a.hi[k], a.lo[k] - b.hi[k]});
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

// True when every corner of box lies on or behind the element's plane: it can see nothing there.
bool behind(const HNode& element, const Bounds& box) {
  const double tol = 1e-9 * (element.radius + 1e-30) + rounding_at(element.center);
  for (int c = 0; c < 8; ++c) {
    const Vec3 p(c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z);
    if (dot(p - element.shape.v[0], element.normal) > tol) return false;
  }
  return true;
}

}  // namespace

void Solver::refine_for_lights() {
  if (!lights()) return;
  std::vector<uint32_t> frontier = std::move(light_frontier_);  // the roots, lit in the constructor
  std::vector<double> spread = std::move(light_spread_);
  while (!frontier.empty()) {
    std::vector<uint32_t> next;
    for (size_t k = 0; k < frontier.size(); ++k) {
      const uint32_t i = frontier[k];
      if (!splittable(i) || luminance(h_[i].rho) * spread[k] * weight(h_[i]) <= eps_) continue;
      h_.subdivide(i);
      ++stats_.light_refinements;
      for (uint32_t c = 0; c < h_[i].child_count; ++c) next.push_back(h_.child(h_[i], c));
    }
    frontier = std::move(next);
    spread = direct_for(frontier);
  }
}

void Solver::mark_two_sided_clusters() {
  if (!s_.twins) return;
  two_sided_.assign(h_.nodes().size(), 0);
  for (uint32_t k = 0; k < h_.nodes().size(); ++k) {
    if (h_[k].cluster || h_[k].depth != 0 || (*s_.twins)[h_[k].polygon] == kNoTwin) continue;
    for (int32_t a = h_[k].parent; a >= 0 && !two_sided_[uint32_t(a)]; a = h_[uint32_t(a)].parent) two_sided_[uint32_t(a)] = 1;
  }
}

bool Solver::splittable(uint32_t i) const {
  const HNode& n = h_[i];
  if (n.cluster) return n.child_count > 0;
  return n.depth < s_.max_depth && n.area * 0.25 >= min_area_;
}

double Solver::estimate(const HNode& ri, const HNode& sj) const {
  const Vec3 d = sj.center - ri.center;
  const double r2 = dot(d, d), r = std::sqrt(r2);
  const bool near = clearly_greater(2.0 * (ri.radius + sj.radius), r);
  const Vec3 u = r > 0 ? d / r : Vec3{};
  const double ci = ri.cluster ? kClusterCosine : (near ? 1.0 : std::max(0.0, dot(ri.normal, u)));
  const double cj = sj.cluster ? kClusterCosine : (near ? 1.0 : std::max(0.0, -dot(sj.normal, u)));
  return ci * cj * sj.area / (kPi * r2 + sj.area);
}

double Solver::oracle(const HNode& ri, const HNode& sj) const {
  return luminance(sj.B) * weight(ri) * luminance(ri.rho) * estimate(ri, sj);
}

void Solver::refine(uint32_t i, uint32_t j, const std::vector<uint32_t>* parent) {
  if (i == j) {
    if (!h_[i].cluster) return;  // a planar element does not see itself
    const uint32_t count = h_[i].child_count;
    for (uint32_t a = 0; a < count; ++a)
      for (uint32_t b = 0; b < count; ++b) refine(h_.child(h_[i], a), h_.child(h_[i], b), parent);
    return;
  }
  {
    const HNode& ri = h_[i];
    const HNode& sj = h_[j];
    if (!ri.cluster && !sj.cluster && ri.polygon == sj.polygon) return;  // coplanar
    if (!ri.cluster && behind(ri, sj.bounds)) return;
    if (!sj.cluster && behind(sj, ri.bounds)) return;
  }
  // A cluster is linked only from far enough away: its bounds at least half its radius from the
  // other end's. Closer, a surface of the cluster may lie centimetres from the other end (a
  // bookcase against a wall), where the point-sampled kernel 1/r² has huge variance and the
  // cluster's average radiosity says nothing of that surface.
  const double reach = std::max(h_[i].cluster ? h_[i].radius : 0.0, h_[j].cluster ? h_[j].radius : 0.0);
  const bool must_split = (reach > 0 && clearly_greater(0.5 * reach, box_distance(h_[i].bounds, h_[j].bounds))) ||
                          two_sided(i) || two_sided(j);
  const bool split = must_split || oracle(h_[i], h_[j]) > eps_;

  // Candidates between the two: the parent's list filtered by this pair's shaft.
  const Shaft shaft(h_[i].bounds, h_[j].bounds);
  const uint32_t ex_i = h_[i].cluster ? UINT32_MAX : h_[i].polygon, ex_j = h_[j].cluster ? UINT32_MAX : h_[j].polygon;
  std::vector<uint32_t> candidates = occluders(i, j, shaft, ex_i, ex_j, parent);

  if (split) {
    const bool si = splittable(i), sj = splittable(j);
    if (si || sj) {
      bool split_receiver = si && (!sj || !clearly_greater(h_[j].radius, h_[i].radius));
      if (must_split && si && sj && h_[i].cluster != h_[j].cluster) split_receiver = h_[i].cluster;
      if (must_split && !(split_receiver ? h_[i].cluster : h_[j].cluster) && (split_receiver ? sj : si) &&
          (split_receiver ? h_[j].cluster : h_[i].cluster))
        split_receiver = !split_receiver;  // split the cluster end first
      const uint32_t end = split_receiver ? i : j;
      h_.subdivide(end);
      ++stats_.refinements;
      const uint32_t count = h_[end].child_count;
      for (uint32_t k = 0; k < count; ++k) {
        const uint32_t c = h_.child(h_[end], k);
        if (split_receiver) refine(c, j, &candidates);
        else refine(i, c, &candidates);
      }
      return;
    }
  }
  // More rays where more can block, and where the transfer matters more than ε (a link kept only
  // because neither end may split further).
  // Volumes count as one blocker: their transmittance varies smoothly, not all or nothing.
  size_t volumes = 0;
  for (uint32_t c : candidates) volumes += (c & kVolumeTags) != 0;
  const size_t blockers = candidates.size() - volumes + (volumes > 0);
  int samples = s_.rays;
  if (blockers > 4) samples *= 2;
  if (blockers > 64) samples *= 2;
  if (split) samples *= 2;
  // The list doubles when full: 2n entries allocated and filled while the n old ones are copied.
  if (s_.checkpoint && pending_.size() == pending_.capacity() && pending_.size() >= 65536)
    s_.checkpoint("refinement", 2 * pending_.capacity() * sizeof(Pending));
  pending_.push_back({i, j, s_.visibility && blockers > size_t(volumes > 0), samples, s_.visibility && volumes > 0});
}

std::vector<uint32_t> Solver::occluders(uint32_t i, uint32_t j, const Shaft& shaft, uint32_t ex_i, uint32_t ex_j,
                                const std::vector<uint32_t>* parent) const {
  const VolumeVisibility* v = s_.volumes;
  if (!v || !s_.visibility)
    return parent ? filter_candidates(h_.tree(), shaft, *parent, ex_i, ex_j) : shaft_candidates(h_.tree(), shaft, ex_i, ex_j);
  const HNode& ri = h_[i];
  const HNode& sj = h_[j];
  const ClusterTree& tree = h_.tree();
  const VolumeClusters& vc = *v->clusters;
  VolumeTags tags{vc.node_in_volume, vc.polygon_in_volume, [&](uint32_t c) {
                    const bool node = c & kVolumeNode;
                    const uint32_t k = c & ~kVolumeTags;
                    const Vec3 at = node ? tree.nodes[k].bounds.center() : tree.polygon_bounds[k].center();
                    const double feature = node ? vc.node_feature[k] : vc.object_width[k];
                    return feature < v->penumbra_ratio * penumbra_width(ri.center, 2 * ri.radius, sj.center, 2 * sj.radius, at);
                  }};
  std::vector<uint32_t> out = parent ? filter_candidates(tree, shaft, *parent, ex_i, ex_j, tags)
                                     : shaft_candidates(tree, shaft, ex_i, ex_j, tags);
  bool tagged = false, exact_volume = false;
  for (uint32_t c : out) {
    if (c & kVolumeTags) tagged = true;
    else if (vc.polygon_in_volume[c]) exact_volume = true;
  }
  if (!tagged || !exact_volume) return out;
  tags.see_through = [](uint32_t) { return false; };
  return filter_candidates(tree, shaft, out, ex_i, ex_j, tags);
}

void Solver::refine_existing() {
  const size_t n = h_.nodes().size();
  for (size_t i = 0; i < n; ++i) {
    if (s_.checkpoint && i % 4096 == 4095) s_.checkpoint("refinement", 0);
    if (h_[i].links.empty()) continue;
    std::vector<Link> links = std::move(h_[i].links);
    h_[i].links.clear();
    // A receiver whose links each pass the oracle may still be wrong as a whole: each link's
    // irradiance is pushed uniformly onto its children, and their true share varies by the
    // links' spreads. When the sum of those variations matters, split the receiver.
    if (!h_[i].cluster && splittable(uint32_t(i))) {
      double variation = 0;
      for (const Link& l : links) variation += luminance(h_[l.source].B) * l.spread;
      if (variation * weight(h_[i]) * luminance(h_[i].rho) > eps_) {
        h_.subdivide(uint32_t(i));
        ++stats_.refinements;
        for (const Link& l : links) {
          --stats_.links;
          for (uint32_t k = 0; k < h_[i].child_count; ++k) refine(h_.child(h_[i], k), l.source, nullptr);
        }
        continue;
      }
    }
    for (const Link& l : links) {
      // A cluster receiver: a link whose transfer lands unevenly on the children (misplaced by the
      // uniform push) goes down to them, alone (its siblings stay where they are accurate).
      if (h_[i].cluster && h_[i].child_count > 0 &&
          luminance(h_[l.source].B) * l.spread * weight(h_[i]) * luminance(h_[i].rho) > eps_) {
        --stats_.links;
        ++stats_.refinements;
        for (uint32_t k = 0; k < h_[i].child_count; ++k) refine(h_.child(h_[i], k), l.source, nullptr);
        continue;
      }
      const bool can = splittable(uint32_t(i)) || splittable(l.source);
      if (can && oracle(h_[i], h_[l.source]) > eps_) {
        --stats_.links;
        refine(uint32_t(i), l.source, nullptr);
      } else {
        h_[i].links.push_back(l);
      }
    }
  }
}

}  // namespace walkrad::hierarchical_detail
