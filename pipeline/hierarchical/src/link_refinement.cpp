// Refinement of the hierarchy's links (Hanrahan, Salzman & Aupperle 1991; clusters: Smits, Arvo &
// Greenberg 1994) by the error each receiver is left with (hierarchical_solver.h): the first pass
// links nodes as high as they may be linked; later passes split the receivers whose transfers fall
// unevenly on them and the sources whose radiosity the receiver needs in finer detail (refinement.h).
// Shafts carry the candidate occluders down; the pairs themselves are refined in pair_refinement.cpp.
#include "refinement.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/core/rounding.h"


namespace walkrad::hierarchical_detail {

Refinement::Refinement(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& s, HierarchicalStats& stats,
                       const ErrorOracle& oracle, Division division, double typical_area)
    : h_(h), rays_(rays), s_(s), stats_(stats), oracle_(oracle), division_(division) {
  mark_two_sided_clusters();
  // Punctual lights: each input polygon's direct irradiance, and how much it varies over it.
  if (lights()) {  // every element is an input polygon's root here
    for (uint32_t i = 0; i < h_.nodes().size(); ++i)
      if (!h_[i].cluster) light_frontier_.push_back(i);
    light_spread_ = direct_for(light_frontier_);
    if (s_.visibility) light_spots_ = light_spots(*s_.lights, h_.scene(), rays_);  // without shadows, no patches
    widen_by_spots(light_frontier_, light_spread_);
  }
  min_area_ = s_.min_area > 0 ? s_.min_area : typical_area;
  stats_.min_area = min_area_;
}

std::vector<LinkRequest> Refinement::take_requests() {
  std::vector<LinkRequest> out;
  out.swap(requests_);
  elsewhere_ = 0;
  return out;
}

void Refinement::forget_light_frontier() {
  std::vector<uint32_t>().swap(light_frontier_);
  std::vector<double>().swap(light_spread_);
  std::vector<LightSpot>().swap(light_spots_);
}

std::vector<double> Refinement::direct_for(const std::vector<uint32_t>& elements) {
  std::vector<double> spread(elements.size(), 0.0);
  std::vector<uint64_t> rays(elements.size(), 0);
  const RayScene* occluders = s_.visibility ? &rays_ : nullptr;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, elements.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k != r.end(); ++k) {
      HNode& n = h_[elements[k]];
      const DirectIrradiance d = direct_irradiance(n.shape, *s_.lights, occluders, 4, rays[k]);
      n.D = d.mean;
      n.D_known = true;
      spread[k] = luminance(n.rho) * d.spread;
      // A transmitting element shows τ times what lights its back as well (a bulb inside a shade:
      // otherwise lamp-room's shade outside is left as coarse as its own dim side asks, 17% off).
      const Vec3 tau = transmittance(n);
      if (max_component(tau) > 0) {
        Polygon back = n.shape;
        std::reverse(back.v.begin(), back.v.begin() + back.count);
        spread[k] += luminance(tau) * direct_irradiance(back, *s_.lights, occluders, 4, rays[k]).spread;
      }
    }
  });
  for (uint64_t r : rays) stats_.light_rays += r;
  return spread;
}

void Refinement::widen_by_spots(const std::vector<uint32_t>& elements, std::vector<double>& spread) {
  if (light_spots_.empty()) return;
  std::unordered_map<uint32_t, size_t> at;  // node → its index in elements
  for (size_t k = 0; k < elements.size(); ++k) at.emplace(elements[k], k);
  std::vector<LightSpot> kept;
  std::vector<int> taken(elements.size(), 0);
  std::vector<std::pair<size_t, Vec3>> probes;  // (element's index, spot)
  for (const LightSpot& spot : light_spots_) {
    const auto it = at.find(leaf_at(h_, h_.polygon_root(spot.polygon), spot.position));
    if (it == at.end()) continue;
    kept.push_back(spot);
    if (taken[it->second]++ < kSpotsPerNode) probes.push_back({it->second, spot.position});
  }
  light_spots_ = std::move(kept);
  std::vector<double> shown(probes.size());
  std::vector<uint64_t> rays(probes.size(), 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, probes.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t j = r.begin(); j != r.end(); ++j)
      shown[j] = luminance(point_irradiance(probes[j].second, h_[elements[probes[j].first]].normal, *s_.lights, &rays_, rays[j]));
  });
  for (size_t j = 0; j < probes.size(); ++j) {
    const HNode& n = h_[elements[probes[j].first]];
    spread[probes[j].first] = std::max(spread[probes[j].first], luminance(n.rho) * std::fabs(shown[j] - luminance(n.D)));
    spot_shown_ = std::max(spot_shown_, luminance(n.rho) * shown[j]);
    stats_.light_rays += rays[j];
  }
}

void Refinement::compute_missing_direct() {
  std::vector<uint32_t> missing;
  for (uint32_t i = 0; i < h_.nodes().size(); ++i)
    if (!h_[i].cluster && !h_[i].D_known) missing.push_back(i);
  direct_for(missing);
}

void Refinement::refine_for_lights() {
  if (!lights()) return;
  std::vector<uint32_t> frontier = std::move(light_frontier_);  // the roots, lit in the constructor
  std::vector<double> spread = std::move(light_spread_);
  while (!frontier.empty()) {
    std::vector<uint32_t> next;
    for (size_t k = 0; k < frontier.size(); ++k) {
      const uint32_t i = frontier[k];
      // Where every sample missed the light (a sun patch only the spots found) nothing is lit yet and
      // the oracle's white is 0: the scale is then what the spots show.
      const double tolerance = oracle_.state().white > 0 || spot_shown_ <= 0 ? oracle_.tolerance(i) : s_.error * spot_shown_;
      if (!splittable(i) || spread[k] <= tolerance) continue;  // spread: of what it shows
      h_.subdivide(i);
      ++stats_.light_refinements;
      for (uint32_t c = 0; c < h_[i].child_count; ++c) next.push_back(h_.child(h_[i], c));
    }
    frontier = std::move(next);
    spread = direct_for(frontier);
    widen_by_spots(frontier, spread);
  }
}

void Refinement::mark_two_sided_clusters() {
  if (!s_.twins) return;
  two_sided_.assign(h_.nodes().size(), 0);
  for (uint32_t k = 0; k < h_.nodes().size(); ++k) {
    if (h_[k].cluster || h_[k].depth != 0 || (*s_.twins)[h_[k].polygon] == kNoTwin) continue;
    for (int32_t a = h_[k].parent; a >= 0 && !two_sided_[uint32_t(a)]; a = h_[uint32_t(a)].parent) two_sided_[uint32_t(a)] = 1;
  }
}

std::vector<uint8_t> Refinement::under_close_pairs() const {
  std::vector<uint8_t> out(h_.nodes().size(), 0);
  if (!oracle_.importance()) return out;  // every close pair matters (close_matters): none is left whole
  for (uint32_t k = 0; k < out.size(); ++k)  // its own links (where they are held)
    for (const Link& l : h_[k].links)
      if (close_pair(h_, k, l.source)) {
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

bool Refinement::splittable(uint32_t i) const {
  const HNode& n = h_[i];
  if (n.cluster) return n.child_count > 0;
  return n.depth < s_.max_depth && n.area * 0.25 >= min_area_;
}

std::vector<uint32_t> Refinement::occluders(uint32_t i, uint32_t j, const Shaft& shaft, uint32_t ex_i, uint32_t ex_j,
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

bool Refinement::ray_free(const Link& l) const {
  // Compact lists and visibility on: rays were cast exactly where the shaft held a candidate.
  return compact() && s_.visibility && (l.rays & 1) == 0;
}

std::vector<uint32_t> Refinement::link_candidates(uint32_t i, const Link& l) const {
  if (ray_free(l)) return {};
  const uint32_t j = l.source;
  return occluders(i, j, Shaft(h_[i].bounds, h_[j].bounds), h_[i].cluster ? UINT32_MAX : h_[i].polygon,
                   h_[j].cluster ? UINT32_MAX : h_[j].polygon, nullptr);
}

void Refinement::recast(uint32_t i, const Link& l) {
  --stats_.links;
  ++stats_.recast;
  add_pending({i, l.source, kHiddenRecast * int(l.samples), (l.rays & 1) != 0, (l.rays & 2) != 0});
}

void Refinement::replace_link(uint32_t i, const Link& l, bool split_receiver, std::vector<uint32_t>& candidates) {
  if (split_receiver) {
    split_link(i, l, candidates);
    return;
  }
  --stats_.links;
  // Ray-free: no candidate, filtered as a parent's empty list; else the pair's own, searched above.
  static const std::vector<uint32_t> kNone;
  const bool none = ray_free(l);
  PairTask t{i, l.source, none ? &kNone : nullptr, true};
  if (!none) {
    t.has_own = true;
    t.own = std::move(candidates);
  }
  queued_pairs_.push_back(std::move(t));
}

void Refinement::split_link(uint32_t i, const Link& l, std::vector<uint32_t>& candidates) {
  // The pair's candidates, searched in the tree once (ReceiverPlan) and filtered for each child
  // (shaft.h: the children's shafts lie inside the pair's), not searched again from the root per child.
  h_.subdivide(i);
  --stats_.links;
  const std::vector<uint32_t>& list = queued_lists_.emplace_back(std::move(candidates));
  for (uint32_t k = 0; k < h_[i].child_count; ++k) queued_pairs_.push_back({h_.child(h_[i], k), l.source, &list});
}

Refinement::ReceiverPlan Refinement::plan_receiver(uint32_t i, bool with_candidates) const {
  ReceiverPlan plan;
  const std::vector<Link>& links = h_[i].links;
  if (links.empty()) return plan;
  // The receiver: its links' transfers, pushed down uniformly, leave its children further apart
  // than its tolerance: every link goes down to the children but the wholly hidden, which stay where
  // what they might carry does not matter, and are first cast again where it does, as below.
  if (clearly_greater(oracle_.state().variation[i], oracle_.tolerance(i)) && splittable(i)) {
    plan.split_receiver = true;
    plan.action.assign(links.size(), kSplit);
    for (size_t k = 0; k < links.size(); ++k) {
      const Link& l = links[k];
      if (recastable(l)) plan.action[k] = oracle_.worth_splitting(i, l.source, true, &l) ? kRecast : kKeep;
      else if (unresolved(l) && !oracle_.worth_splitting(i, l.source, true, &l)) plan.action[k] = kKeep;
    }
    if (!with_candidates) return plan;
    plan.candidates.resize(links.size());
    for (size_t k = 0; k < links.size(); ++k)
      if (plan.action[k] == kSplit) plan.candidates[k] = link_candidates(i, links[k]);
    return plan;
  }
  // Each link: one that carries more than its share is refined again from here (refine splits it).
  // A link whose every ray was blocked is first cast again with kHiddenRecast times the rays (a few
  // rays miss a gap); still unresolved, it is refined while what it might carry matters.
  plan.action.assign(links.size(), kKeep);
  for (size_t k = 0; k < links.size(); ++k) {
    const Link& l = links[k];
    if (recastable(l) && oracle_.worth_splitting(i, l.source, true, &l)) {
      plan.action[k] = kRecast;
    } else if (!recastable(l) && (splittable(i) || splittable(l.source)) && oracle_.worth_splitting(i, l.source, l.rays != 0, &l)) {
      plan.action[k] = kSplit;
      if (!with_candidates) continue;
      if (plan.candidates.empty()) plan.candidates.resize(links.size());  // most receivers split none
      plan.candidates[k] = link_candidates(i, l);
    }
  }
  return plan;
}

void Refinement::refine_existing() {
  // What to do with each receiver's links depends only on the state before this pass: a split adds
  // nodes and pending links but changes no existing node's links, radiosity, bounds or measures. So
  // the decisions and the split links' candidate lists (searched from the tree's root: a quarter of the
  // refinement's time) are made in parallel, a batch of receivers at a time, and applied in order; the
  // pairs they hand on are refined with the batch's others (refine_pairs: level by level, each level
  // decided in parallel and applied in order): nodes and links come out the same whatever the thread
  // count.
  // Divisible (Jacobi sweeps, link_owners.h): the element receivers' plans are made first, all from
  // the state before the pass, by the ranks that hold their links, and sent to every rank.
  constexpr size_t kBatch = 1024;
  const size_t n = h_.nodes().size();
  std::vector<uint32_t> plan_of;
  std::vector<RemotePlan> remote;
  if (division_.divisible) exchange_plans(plan_of, remote);
  auto remote_plan = [&](size_t at) { return division_.divisible && !h_[uint32_t(at)].cluster; };
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
      plan = ReceiverPlan{};  // its lists are spent (or handed on): free them now
    }
    refine_pairs(std::move(queued_pairs_));
    queued_pairs_.clear();
    queued_lists_.clear();
  }
}

thread_local std::vector<uint8_t> Refinement::blocked_scratch_;
thread_local std::vector<RayScene::Segment> Refinement::probe_scratch_;

}  // namespace walkrad::hierarchical_detail
