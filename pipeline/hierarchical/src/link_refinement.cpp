// Refinement of the hierarchy's links (Hanrahan, Salzman & Aupperle 1991; clusters: Smits, Arvo &
// Greenberg 1994) by the error each receiver is left with (hierarchical_solver.h): the first pass
// links nodes as high as they may be linked; later passes split the receivers whose transfers fall
// unevenly on them and the sources whose radiosity the receiver needs in finer detail. Shafts carry
// the candidate occluders down.
#include "solver.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/core/rounding.h"

namespace walkrad::hierarchical_detail {

namespace {

// Distance between two boxes (0 when they overlap or touch).
double box_distance(const Bounds& a, const Bounds& b) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({0.0, b.lo[k] - a.hi[k], a.lo[k] - b.hi[k]});
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

// True when every point of the other node lies on or behind the element's plane: the element sees
// nothing of it. An element other is tested by its corners (a convex polygon lies behind a plane when
// they do), a cluster by its box's: the boxes of two tilted facets side by side on a convex object
// (a chair's, a lamp's) reach in front of each other's planes, and the pair was linked, cast its rays
// and dropped (half of MGF office3's first links, 39% of their rays).
bool behind(const HNode& element, const HNode& other) {
  const double tol = 1e-9 * (element.radius + 1e-30) + rounding_at(element.center);
  auto in_front = [&](const Vec3& p) { return dot(p - element.shape.v[0], element.normal) > tol; };
  if (!other.cluster) {
    for (int k = 0; k < other.shape.count; ++k)
      if (in_front(other.shape.v[size_t(k)])) return false;
    return true;
  }
  const Bounds& box = other.bounds;
  for (int c = 0; c < 8; ++c)
    if (in_front(Vec3(c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z))) return false;
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
      if (!splittable(i) || spread[k] <= tolerance(i)) continue;  // spread: of what it shows
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

bool Solver::close_pair(uint32_t i, uint32_t j) const {
  const double reach = std::max(h_[i].cluster ? h_[i].radius : 0.0, h_[j].cluster ? h_[j].radius : 0.0);
  return reach > 0 && clearly_greater(0.5 * reach, box_distance(h_[i].bounds, h_[j].bounds));
}

std::vector<uint8_t> Solver::under_close_pairs() const {
  std::vector<uint8_t> out(h_.nodes().size(), 0);
  if (!importance_) return out;  // every close pair matters (close_matters): none is left whole
  for (uint32_t k = 0; k < out.size(); ++k)  // its own links (where they are held)
    for (const Link& l : h_[k].links)
      if (close_pair(k, l.source)) {
        out[k] = 1;
        break;
      }
  share_element_values(h_, out);
  for (uint32_t k = 0; k < out.size(); ++k) {  // parents first
    const int32_t parent = h_[k].parent;
    if (parent >= 0 && out[size_t(parent)]) out[k] = 1;
  }
  return out;
}

bool Solver::splittable(uint32_t i) const {
  const HNode& n = h_[i];
  if (n.cluster) return n.child_count > 0;
  return n.depth < s_.max_depth && n.area * 0.25 >= min_area_;
}

void Solver::self_pairs(uint32_t i, std::vector<std::pair<uint32_t, uint32_t>>& pairs) const {
  if (!h_[i].cluster) return;
  const uint32_t count = h_[i].child_count;
  for (uint32_t a = 0; a < count; ++a)
    for (uint32_t b = 0; b < count; ++b) {
      const uint32_t ca = h_.child(h_[i], a), cb = h_.child(h_[i], b);
      if (ca == cb) self_pairs(ca, pairs);
      else pairs.push_back({ca, cb});
    }
}

void Solver::refine_first() {
  // refine(root, root) comes down to refine(a, b) for the pairs self_pairs lists, in that order. Before
  // the first solve only cluster ends split (nothing is solved, so only a cluster too close or a
  // two-sided one forces a split, and it is the cluster end that splits): the pairs are refined in
  // parallel, each into its own list, and the lists joined in order, as one serial pass would have
  // made them. Should an element need splitting (a node made: order matters), the pass is made again
  // serially.
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  self_pairs(h_.root(), pairs);
  std::vector<std::vector<NewLink>> found(pairs.size());
  std::vector<uint64_t> splits(pairs.size(), 0);
  std::atomic<bool> blocked{false};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pairs.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k != r.end() && !blocked; ++k) {
      Refinement out{&found[k], splits[k]};
      refine(out, pairs[k].first, pairs[k].second, nullptr);
      if (out.blocked) blocked = true;
    }
  });
  if (blocked) {
    Refinement out = serial_refinement();
    refine(out, h_.root(), h_.root(), nullptr);
    return;
  }
  size_t total = 0;
  for (const std::vector<NewLink>& f : found) total += f.size();
  if (s_.check_limits) s_.check_limits("refinement", (pending_.size() + total) * sizeof(Pending));
  pending_.reserve(pending_.size() + total);
  for (size_t k = 0; k < pairs.size(); ++k) {
    for (const NewLink& f : found[k]) add_pending({f.receiver, f.source, f.need_rays, f.samples, f.volume});
    stats_.refinements += splits[k];
    std::vector<NewLink>().swap(found[k]);
  }
}

void Solver::refine(Refinement& out, uint32_t i, uint32_t j, const std::vector<uint32_t>* parent, bool force,
                    std::vector<uint32_t>* own) {
  if (i == j) {
    if (!h_[i].cluster) return;  // a planar element does not see itself
    const uint32_t count = h_[i].child_count;
    for (uint32_t a = 0; a < count; ++a)
      for (uint32_t b = 0; b < count; ++b) refine(out, h_.child(h_[i], a), h_.child(h_[i], b), parent);
    return;
  }
  {
    const HNode& ri = h_[i];
    const HNode& sj = h_[j];
    if (!ri.cluster && !sj.cluster && ri.polygon == sj.polygon) return;  // coplanar
    if (!ri.cluster && behind(ri, sj)) return;
    if (!sj.cluster && behind(sj, ri)) return;
  }
  // A cluster is linked only from far enough away (close_pair): closer, a surface of the cluster may
  // lie centimetres from the other end (a bookcase against a wall), where the point-sampled kernel
  // 1/r² has huge variance and the cluster's average radiosity says nothing of that surface. Where the
  // walkthrough does not look the pair stays whole (close_matters; its kernel bounded: evaluate; its
  // receivers' rows left unscaled: under_close_pairs).
  const bool must_split = (close_pair(i, j) && close_matters(i)) || two_sided(i) || two_sided(j);

  // Candidates between the two: the parent's list filtered by this pair's shaft.
  const Shaft shaft(h_[i].bounds, h_[j].bounds);
  const uint32_t ex_i = h_[i].cluster ? UINT32_MAX : h_[i].polygon, ex_j = h_[j].cluster ? UINT32_MAX : h_[j].polygon;
  // With compact lists from a parent, the list itself is built only for a pair that splits again;
  // a pair that becomes a link needs only its count, up to the thresholds below.
  const bool lazy = compact() && parent;
  std::vector<uint32_t> candidates;
  if (!lazy) candidates = own ? std::move(*own) : occluders(i, j, shaft, ex_i, ex_j, parent);
  const size_t listed = lazy ? count_compact_candidates(h_.tree(), shaft, *parent, ex_i, ex_j, kManyBlockers + 1)
                        : compact() ? candidate_count(h_.tree(), candidates, ex_i, ex_j)
                                    : candidates.size();
  const bool split = force || must_split || worth_splitting(i, j, listed > 0);

  if (split) {
    const bool si = splittable(i), sj = splittable(j);
    if (si || sj) {
      bool split_receiver = si && (!sj || !clearly_greater(h_[j].radius, h_[i].radius));
      if (must_split && si && sj && h_[i].cluster != h_[j].cluster) split_receiver = h_[i].cluster;
      if (must_split && !(split_receiver ? h_[i].cluster : h_[j].cluster) && (split_receiver ? sj : si) &&
          (split_receiver ? h_[j].cluster : h_[i].cluster))
        split_receiver = !split_receiver;  // split the cluster end first
      const uint32_t end = split_receiver ? i : j;
      if (out.found && !h_[end].cluster && h_[end].child_count == 0) {
        out.blocked = true;  // a node to make: not while other pairs are refined
        return;
      }
      if (lazy) candidates = occluders(i, j, shaft, ex_i, ex_j, parent);
      h_.subdivide(end);
      ++out.refinements;
      const uint32_t count = h_[end].child_count;
      for (uint32_t k = 0; k < count && !out.blocked; ++k) {
        const uint32_t c = h_.child(h_[end], k);
        if (split_receiver) refine(out, c, j, &candidates);
        else refine(out, i, c, &candidates);
      }
      return;
    }
  }
  // More rays where more can block.
  // Volumes count as one blocker: their transmittance varies smoothly, not all or nothing.
  size_t volumes = 0;
  for (uint32_t c : candidates) volumes += (c & kVolumeTags) != 0;
  const size_t blockers = listed - volumes + (volumes > 0);
  int samples = s_.rays;
  if (blockers > kSomeBlockers) samples *= 2;
  if (blockers > kManyBlockers) samples *= 2;
  // The list doubles when full: 2n entries allocated and filled while the n old ones are copied.
  const bool need_rays = s_.visibility && blockers > size_t(volumes > 0), volume = s_.visibility && volumes > 0;
  if (out.found) {
    out.found->push_back({i, j, samples, need_rays, volume});
    return;
  }
  if (s_.check_limits && pending_.size() == pending_.capacity() && pending_.size() >= 65536)
    s_.check_limits("refinement", 2 * pending_.capacity() * sizeof(Pending));
  add_pending({i, j, need_rays, samples, volume});
}

std::vector<uint32_t> Solver::occluders(uint32_t i, uint32_t j, const Shaft& shaft, uint32_t ex_i, uint32_t ex_j,
                                const std::vector<uint32_t>* parent) const {
  if (compact())
    return parent ? filter_compact_candidates(h_.tree(), shaft, *parent, ex_i, ex_j) : compact_candidates(h_.tree(), shaft, ex_i, ex_j);
  const VolumeVisibility* v = s_.volumes;
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

bool Solver::ray_free(const Link& l) const {
  // Compact lists and visibility on: rays were cast exactly where the shaft held a candidate.
  return compact() && s_.visibility && (l.rays & 1) == 0;
}

std::vector<uint32_t> Solver::link_candidates(uint32_t i, const Link& l) const {
  if (ray_free(l)) return {};
  const uint32_t j = l.source;
  return occluders(i, j, Shaft(h_[i].bounds, h_[j].bounds), h_[i].cluster ? UINT32_MAX : h_[i].polygon,
                   h_[j].cluster ? UINT32_MAX : h_[j].polygon, nullptr);
}

void Solver::recast(uint32_t i, const Link& l) {
  --stats_.links;
  ++stats_.recast;
  add_pending({i, l.source, (l.rays & 1) != 0, kHiddenRecast * int(l.samples), (l.rays & 2) != 0});
}

void Solver::replace_link(uint32_t i, const Link& l, bool split_receiver, std::vector<uint32_t>& candidates) {
  if (split_receiver) {
    split_link(i, l, candidates);
    return;
  }
  --stats_.links;
  static const std::vector<uint32_t> kNone;
  // Ray-free: no candidate, filtered as a parent's empty list; else the pair's own, searched above.
  Refinement out = serial_refinement();
  refine(out, i, l.source, ray_free(l) ? &kNone : nullptr, true, &candidates);
}

void Solver::split_link(uint32_t i, const Link& l, const std::vector<uint32_t>& candidates) {
  // The pair's candidates, searched in the tree once (ReceiverPlan) and filtered for each child
  // (shaft.h: the children's shafts lie inside the pair's), not searched again from the root per child.
  const uint32_t j = l.source;
  h_.subdivide(i);
  --stats_.links;
  Refinement out = serial_refinement();
  for (uint32_t k = 0; k < h_[i].child_count; ++k) refine(out, h_.child(h_[i], k), j, &candidates);
}

Solver::ReceiverPlan Solver::plan_receiver(uint32_t i, bool with_candidates) const {
  ReceiverPlan plan;
  const std::vector<Link>& links = h_[i].links;
  if (links.empty()) return plan;
  // The receiver: its links' transfers, pushed down uniformly, leave its children further apart
  // than its tolerance: every link goes down to the children but the wholly hidden, which stay, settled
  // (settled_hidden) or to be cast again where what they might carry matters, as below.
  if (clearly_greater(variation_[i], tolerance(i)) && splittable(i)) {
    plan.split_receiver = true;
    plan.action.assign(links.size(), kSplit);
    for (size_t k = 0; k < links.size(); ++k) {
      const Link& l = links[k];
      if (recastable(l)) plan.action[k] = worth_splitting(i, l.source, true, nullptr) ? kRecast : kKeep;
      else if (settled_hidden(l)) plan.action[k] = kKeep;
    }
    if (!with_candidates) return plan;
    plan.candidates.resize(links.size());
    for (size_t k = 0; k < links.size(); ++k)
      if (plan.action[k] == kSplit) plan.candidates[k] = link_candidates(i, links[k]);
    return plan;
  }
  // Each link: one that carries more than its share is refined again from here (refine splits it).
  // A link whose every ray was blocked is first cast again with kHiddenRecast times the rays: a few
  // rays miss a gap, and a wall between two rooms should not be refined for what they might miss.
  plan.action.assign(links.size(), kKeep);
  for (size_t k = 0; k < links.size(); ++k) {
    const Link& l = links[k];
    if (recastable(l) && worth_splitting(i, l.source, true, nullptr)) {
      plan.action[k] = kRecast;
    } else if (!settled_hidden(l) && (splittable(i) || splittable(l.source)) && worth_splitting(i, l.source, l.rays != 0, &l)) {
      plan.action[k] = kSplit;
      if (!with_candidates) continue;
      if (plan.candidates.empty()) plan.candidates.resize(links.size());  // most receivers split none
      plan.candidates[k] = link_candidates(i, l);
    }
  }
  return plan;
}

void Solver::refine_existing() {
  update_scales();
  measure_variation();
  // What to do with each receiver's links depends only on the state before this pass: a split adds
  // nodes and pending links but changes no existing node's links, radiosity, bounds or measures. So
  // the decisions and the split links' candidate lists (searched from the tree's root: a quarter of the
  // refinement's time) are made in parallel, a batch of receivers at a time, and applied in order:
  // nodes and links come out exactly as from one serial pass, whatever the thread count.
  // Divisible (Jacobi sweeps, link_owners.h): the element receivers' plans are made first, all from
  // the state before the pass, by the ranks that hold their links, and sent to every rank.
  constexpr size_t kBatch = 1024;
  const size_t n = h_.nodes().size();
  std::vector<uint32_t> plan_of;
  std::vector<RemotePlan> remote;
  if (divisible_) exchange_plans(plan_of, remote);
  auto remote_plan = [&](size_t at) { return divisible_ && !h_[uint32_t(at)].cluster; };
  std::vector<ReceiverPlan> plans;
  for (size_t first = 0; first < n; first += kBatch) {
    const size_t last = std::min(n, first + kBatch);
    plans.assign(last - first, ReceiverPlan{});
    tbb::parallel_for(tbb::blocked_range<size_t>(first, last, 16), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t at = r.begin(); at != r.end(); ++at) {
        if (!remote_plan(at)) plans[at - first] = plan_receiver(uint32_t(at));
        else if (plan_of[at] != UINT32_MAX) plans[at - first].candidates = remote_candidates(uint32_t(at), remote[plan_of[at]]);
      }
    });
    for (size_t at = first; at < last; ++at) {
      const uint32_t i = uint32_t(at);
      if (s_.check_limits && i % 4096 == 4095) s_.check_limits("refinement", 0);
      if (remote_plan(at)) {
        if (plan_of[at] != UINT32_MAX) apply_plan(i, remote[plan_of[at]], plans[at - first].candidates);
        plans[at - first] = ReceiverPlan{};
        continue;
      }
      if (h_[i].links.empty()) continue;
      ReceiverPlan& plan = plans[at - first];
      std::vector<Link> links = std::move(h_[i].links);
      h_[i].links.clear();
      if (plan.split_receiver) {
        ++stats_.refinements;
        ++stats_.receiver_splits;
      }
      h_[i].links.reserve(size_t(std::count(plan.action.begin(), plan.action.end(), kKeep)));  // exact: see evaluate_pending
      for (size_t k = 0; k < links.size(); ++k)
        if (plan.action[k] == kKeep) h_[i].links.push_back(links[k]);
      for (size_t k = 0; k < links.size(); ++k) {
        if (plan.action[k] == kRecast) recast(i, links[k]);
        else if (plan.action[k] == kSplit) replace_link(i, links[k], plan.split_receiver, plan.candidates[k]);
      }
      plan = ReceiverPlan{};  // its lists are spent: free them now
    }
  }
}

}  // namespace walkrad::hierarchical_detail
