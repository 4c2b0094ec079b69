// The solve's sweeps (sweeps.h): gather along the links, push-pull radiosity down and up the hierarchy,
// shoot and push-pull importance (Hanrahan, Salzman & Aupperle 1991; importance: Smits, Arvo & Salesin 1992).
#include "sweeps.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/hierarchical/cluster_radiosity.h"
#include "walkrad/hierarchical/directional_irradiance.h"
#include "walkrad/hierarchical/hierarchy_walk.h"
#include "walkrad/hierarchical/link_transport.h"
#include "walkrad/hierarchical/transmission.h"
#include "link_evaluator.h"

namespace walkrad::hierarchical_detail {

Sweeps::Sweeps(Hierarchy& h, const HierarchicalSettings& s, const ErrorOracle& oracle, Division division)
    : h_(h), s_(s), oracle_(oracle), division_(division) {
  // Every cluster exists from the start; only they gather by direction (192 bytes each: kept by node,
  // a 150-room level's 748,742 element roots held 144 MB of them unused). By HNode::tree_node.
  state_.cube.assign(h_.cluster_count(), DirectionalIrradiance{});
}

void Sweeps::measure_change_floor() {
  for (const HNode& n : h_.nodes())
    if (!n.cluster) change_floor_ = std::max(change_floor_, 1e-9 * max_component(n.emission + mul(n.rho, n.D)));
}

Vec3 Sweeps::twin_irradiance(const HNode& n) const { return twin_received(h_, n, (*s_.twins)[n.polygon]); }

double Sweeps::twin_importance(const HNode& n) const {
  const uint32_t t = twin_node(h_, n, (*s_.twins)[n.polygon]);
  return h_[t].area > 0 ? h_[t].I * std::min(1.0, n.area / h_[t].area) : 0.0;
}

double Sweeps::sweep(IterationStats& is, bool with_importance, double relaxation) {
  relax_ = relaxation;
  HNodes& nodes = h_.nodes();
  // What each cluster sends by direction, from the last sweep's radiosity; Gauss-Seidel sweeps then
  // update a cluster's as its surfaces are updated (push_pull), and gather at a cluster as they reach
  // it. Read from the last sweep instead, a lamp's top 1 cm under a ceiling and the ceiling above it,
  // linked through clusters, would swap their excess every sweep (a Jacobi step, eigenvalues ±ρF):
  // office-floor's last round at 8 rooms takes 15 sweeps this way, against 23.
  if (s_.indirect) facing_radiosity(h_, [&](uint32_t k) { return nodes[k].Bt; }, facing_bt_);
  if (!s_.gauss_seidel)  // Jacobi: every node gathers first (Gauss-Seidel gathers in push_pull)
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i)
        if (here(uint32_t(i))) gather(nodes[i]);
    });
  next_block_ = 0;
  if (division_.divided) share_gathered();
  state_.change = 0;
  is.emitted = is.absorbed = is.residual = Vec3{};
  is.clamped_leaves = 0;
  push_pull(h_.root(), Vec3{}, 0.0, DirectionalIrradiance{}, is);
  if (oracle_.importance() && with_importance) {
    if (division_.divisible) {
      shoot_importance_exactly();
    } else {
      // Sequential: sums in a fixed order. Into an array of their own, not the nodes' Ig: each link
      // adds to a source far from the last, and a node is hundreds of bytes (a cache miss each).
      std::vector<double>& shot = shot_scratch_;
      shot.assign(nodes.size(), 0.0);
      // To the parts of the source its light comes from (for_each_part, Link::seen): the adjoint of
      // the gather, so that a corridor's 320 m floor seen near one door takes its importance near that
      // door, not spread by area over its length.
      for (const HNode& n : nodes) {
        const double rho = luminance(n.rho);
        for (const Link& l : n.links)
          if (carries(l)) for_each_part(h_, l, [&](uint32_t part, double w) { shot[part] += rho * l.F * n.I * w; });
      }
      tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k != r.end(); ++k) nodes[k].Ig = shot[k];
      });
    }
    push_pull_importance(h_.root(), 0.0);
  }
  return state_.change;
}

void Sweeps::gather(HNode& n) {
  // One pass over the links, each source's radiosity read once. A cluster keeps its transfers by
  // direction (directional_irradiance.h); an element gives each child its share of every link
  // (Link::share). Set here so that a Jacobi sweep pushes what it gathered.
  DirectionalIrradiance* cube = n.cluster ? &state_.cube[n.tree_node] : nullptr;
  if (cube) *cube = {};
  const uint32_t shared = n.cluster ? 0 : std::min<uint32_t>(n.child_count, 4);
  for (uint32_t k = 0; k < n.child_count; ++k) {
    HNode& c = h_[h_.child(n, k)];
    c.Hp = Vec3{};
    c.Fp = 0;
  }
  Vec3 H;
  double f = 0;
  for (const Link& l : n.links) {
    if (!carries(l)) continue;
    const HNode& source = h_[l.source];
    const Vec3 b = sent_to(n, l);
    H += b * l.F;
    f += l.F;
    if (cube) cube->add(n, link_direction(n, source), l.F, b);
    for (uint32_t k = 0; k < shared; ++k) {
      HNode& c = h_[h_.child(n, k)];
      const double share = l.F * double(l.share[k]);
      c.Hp += b * share;
      c.Fp += share;
    }
  }
  n.H = H;
  n.Fsum = f;
}

Vec3 Sweeps::sent_to(const HNode& n, const Link& l) const {
  return link_radiosity_towards(h_, l, n.center, facing_bt_, [&](uint32_t node) { return sent(s_, h_[node]); });
}

void Sweeps::plan_gather_blocks() {
  // The nodes that gather in the walk's order (push_pull: a node, then its children in turn): each
  // cluster, and each polygon's whole element tree at once (its elements gather from other polygons
  // only). A polygon's nodes change when the walk pushes it; a cluster's value (Bt, facing_bt_, its
  // parts') when the walk leaves it, after every item below it.
  std::vector<uint32_t> items, first(state_.cube.size()), last(state_.cube.size());
  std::vector<uint32_t> polygon_item(h_.scene().polygons.size(), UINT32_MAX);
  std::vector<uint32_t> stack{h_.root()};
  while (!stack.empty()) {
    const uint32_t i = stack.back();
    stack.pop_back();
    if (i == UINT32_MAX) {  // a cluster's subtree ends: its last item
      const uint32_t c = stack.back();
      stack.pop_back();
      last[h_[c].tree_node] = uint32_t(items.size() - 1);
      continue;
    }
    const HNode& n = h_[i];
    if (!n.cluster) {
      polygon_item[n.polygon] = uint32_t(items.size());
      items.push_back(i);
      continue;
    }
    first[n.tree_node] = uint32_t(items.size());
    items.push_back(i);
    stack.push_back(i);
    stack.push_back(UINT32_MAX);
    for (uint32_t c = n.child_count; c-- > 0;) stack.push_back(h_.child(n, c));
  }
  // An item joins the open block when none of its links reads a node the walk changes between the
  // block's start and the item's turn: gathered at the block's start, it reads what it would read at
  // its turn, and every sweep gives the same bytes as one node at a time.
  block_nodes_.clear();
  block_start_.clear();
  uint32_t open = 0;  // the open block's first item
  // Whether a link of block_nodes_[from...] reads a polygon pushed, or a cluster left, since item open.
  auto reads_open_block = [&](size_t from, uint32_t t) {
    for (size_t k = from; k < block_nodes_.size(); ++k)
      for (const Link& l : h_[block_nodes_[k]].links) {
        if (!carries(l)) continue;  // gather passes over it: whatever its source holds, it adds 0
        const HNode& source = h_[l.source];
        const uint32_t lo = source.cluster ? first[source.tree_node] : polygon_item[source.polygon];
        const uint32_t hi = source.cluster ? last[source.tree_node] : lo;
        if (lo < t && hi >= open) return true;
      }
    return false;
  };
  for (uint32_t t = 0; t < items.size(); ++t) {
    const size_t from = block_nodes_.size();
    block_nodes_.push_back(items[t]);
    if (!h_[items[t]].cluster)
      for (size_t k = from; k < block_nodes_.size(); ++k)
        for (uint32_t c = 0; c < h_[block_nodes_[k]].child_count; ++c) block_nodes_.push_back(h_.child(h_[block_nodes_[k]], c));
    if (t == 0 || !s_.gather_blocks || reads_open_block(from, t)) {
      open = t;
      block_start_.push_back(from);
    }
  }
  block_start_.push_back(block_nodes_.size());
}

void Sweeps::gather_block(size_t b) {
  // Each node writes its own H and its children's Hp and reads only what push_pull writes.
  tbb::parallel_for(tbb::blocked_range<size_t>(block_start_[b], block_start_[b + 1], 16), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k != r.end(); ++k) gather(h_[block_nodes_[k]]);
  });
}

Vec3 Sweeps::push_pull(uint32_t i, const Vec3& down, double down_sum, const DirectionalIrradiance& cube, IterationStats& is) {
  // The walk reaches a block at its first node (plan_gather_blocks).
  if (s_.gauss_seidel && next_block_ + 1 < block_start_.size() && block_nodes_[block_start_[next_block_]] == i)
    gather_block(next_block_++);
  HNode& n = h_[i];
  if (n.child_count == 0) {
    Vec3 H = n.H + down;
    const double row_sum = n.Fsum + down_sum;
    bool clamped = false;
    H = leaf_irradiance(n, H, row_sum, &clamped);
    if (clamped) ++is.clamped_leaves;
    const Vec3 tau = simulated_transmittance(h_, s_, n);
    const Vec3 through = tau == Vec3{} ? Vec3{} : mul(tau, twin_irradiance(n));
    auto radiosity = [&](const Vec3& irradiance) { return n.emission + mul(n.rho, irradiance + n.D) + through; };
    const Vec3 gathered = radiosity(H);
    if (relax_ != 1.0) {  // over-relaxed: past the gathered value, never below 0
      const Vec3 r = n.Hl + (H - n.Hl) * relax_;
      H = Vec3(std::max(r.x, 0.0), std::max(r.y, 0.0), std::max(r.z, 0.0));
    }
    h_[i].Hl = H;
    const Vec3 b = relax_ != 1.0 ? radiosity(H) : gathered;
    // The change, relative to the leaf's radiosity and weighed by what the walkthrough sees of it
    // (display_weight: 1 without importance), as its refinement tolerance is: a room no viewpoint sees
    // nor lights through others need not converge further than what it sends into the seen ones.
    const double scale = std::max(max_component(b), change_floor_);
    if (scale > 0)
      state_.change = std::max(state_.change, oracle_.display_weight(i) * max_component(Vec3(std::fabs(gathered.x - n.B.x), std::fabs(gathered.y - n.B.y), std::fabs(gathered.z - n.B.z))) / scale);
    // The residual of the leaf's equation before this update: |E + ρH − B| A.
    const Vec3 r = b - n.B;
    is.residual += Vec3(std::fabs(r.x), std::fabs(r.y), std::fabs(r.z)) * n.area;
    n.B = b;
    n.Bt = b * n.send;
    is.emitted += (n.emission + n.D) * n.area;
    is.absorbed += mul(Vec3(1, 1, 1) - n.rho - tau, H + n.D) * n.area;
    return b;
  }
  Vec3 sum, sent;
  const uint32_t count = n.child_count;
  const double area = n.area;
  DirectionalIrradiance total = cube;
  if (n.cluster) total += state_.cube[n.tree_node];
  for (uint32_t k = 0; k < count; ++k) {
    const uint32_t c = h_.child(h_[i], k);
    const HNode& child = h_[c];
    if (child.cluster) {
      sum += push_pull(c, down, down_sum, total, is) * child.area;
    } else if (n.cluster) {  // an element root: the directional irradiance, taken by its normal
      sum += push_pull(c, down + total.at(child.normal), down_sum + total.row(child.normal), DirectionalIrradiance{}, is) * child.area;
    } else {
      sum += push_pull(c, down + child.Hp, down_sum + child.Fp, DirectionalIrradiance{}, is) * child.area;
    }
    sent += h_[c].Bt * h_[c].area;
  }
  h_[i].B = area > 0 ? sum / area : Vec3{};
  h_[i].Bt = area > 0 ? sent / area : Vec3{};
  // What the cluster sends by direction, from its surfaces as they now are: links from it read this
  // sweep's radiosity, as links from elements do.
  if (s_.gauss_seidel && n.cluster && n.tree_node < facing_bt_.size())
    facing_bt_[n.tree_node] = facing_from_children(h_, i, facing_bt_, [&](uint32_t k) { return h_[k].Bt; });
  return h_[i].B;
}

double Sweeps::push_pull_importance(uint32_t i, double down) {
  const double total = h_[i].Ig + down;
  if (h_[i].child_count == 0) {
    // Importance passes through a transmitting surface as light does, τ of it to the twin at the
    // same place: what lights the inside of a shade is seen through it (lamp-room: the shade's inside,
    // seen by no viewpoint, stayed one element a face and its outside took that element's mean).
    const Vec3 tau = simulated_transmittance(h_, s_, h_[i]);
    const double through = max_component(tau) > 0 ? luminance(tau) * twin_importance(h_[i]) : 0.0;
    return h_[i].I = h_[i].R + total + through;
  }
  const HNode& n = h_[i];
  const double area = n.area;
  auto child = [&](uint32_t k) {
    const uint32_t c = h_.child(n, k);
    return push_pull_importance(c, area > 0 ? total * h_[c].area / area : 0.0);
  };
  double sum = 0;
  // A large cluster's subtrees on other threads (hierarchy_walk.h), their sums added in child order:
  // the bits of the serial walk. Not with twins, whose leaves read their twin's I as last pushed.
  if (!s_.twins && n.cluster && h_.polygon_count(n) >= kParallelPolygons) {
    std::vector<double> part(n.child_count);
    tbb::parallel_for(uint32_t(0), n.child_count, [&](uint32_t k) { part[k] = child(k); });
    for (double v : part) sum += v;
  } else {
    for (uint32_t k = 0; k < n.child_count; ++k) sum += child(k);
  }
  return h_[i].I = sum;
}

}  // namespace walkrad::hierarchical_detail
