// The solver's steps as a divided solve runs them (link_owners.h, docs/scaling.md): each rank keeps
// the links of its own receivers, makes their refinement plans and their gathers, and sends the others
// what those give per node; everything that creates nodes or links runs on every rank, in one order,
// from values every rank holds. With Jacobi sweeps the same steps run in one process (divisible_), so
// that a bake over N ranks is the bake of one.
#include "solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace walkrad::hierarchical_detail {

void Solver::exchange_plans(std::vector<uint32_t>& plan_of, std::vector<RemotePlan>& plans) const {
  // This rank's plans as words: the receiver, the count of listed links (| 1 << 31 where the receiver
  // splits), then per link its index, its source, and samples | rays << 16 | action << 24.
  const size_t n = h_.nodes().size();
  std::vector<uint32_t> words;
  constexpr size_t kBatch = 4096;
  std::vector<ReceiverPlan> batch;
  for (size_t first = 0; first < n; first += kBatch) {
    const size_t last = std::min(n, first + kBatch);
    batch.assign(last - first, ReceiverPlan{});
    tbb::parallel_for(tbb::blocked_range<size_t>(first, last, 16), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t at = r.begin(); at != r.end(); ++at)
        if (!h_[uint32_t(at)].cluster && here(uint32_t(at))) batch[at - first] = plan_receiver(uint32_t(at), false);
    });
    for (size_t at = first; at < last; ++at) {
      const ReceiverPlan& p = batch[at - first];
      const std::vector<Link>& links = h_[uint32_t(at)].links;
      size_t listed = 0;
      for (size_t k = 0; k < links.size(); ++k) listed += k < p.action.size() && p.action[k] != kKeep;
      if (listed == 0) continue;
      words.push_back(uint32_t(at));
      words.push_back(uint32_t(listed) | (p.split_receiver ? 1u << 31 : 0u));
      for (size_t k = 0; k < links.size(); ++k) {
        const uint8_t action = uint8_t(p.action[k]);
        if (action == kKeep) continue;
        const Link& l = links[k];
        words.push_back(uint32_t(k));
        words.push_back(l.source);
        words.push_back(uint32_t(l.samples) | uint32_t(l.rays) << 16 | uint32_t(action) << 24);
      }
    }
  }
  std::vector<uint8_t> mine(words.size() * sizeof(uint32_t));
  if (!words.empty()) std::memcpy(mine.data(), words.data(), mine.size());
  std::vector<uint32_t>().swap(words);
  const std::vector<uint8_t> all = divided_ ? all_gather(mine) : std::move(mine);
  auto word = [&](size_t k) {
    uint32_t w;
    std::memcpy(&w, all.data() + k * sizeof(uint32_t), sizeof(w));
    return w;
  };
  plan_of.assign(n, UINT32_MAX);
  plans.clear();
  for (size_t k = 0; k < all.size() / sizeof(uint32_t);) {
    const uint32_t receiver = word(k), head = word(k + 1);
    RemotePlan plan;
    plan.split_receiver = (head >> 31) != 0;
    plan.links.resize(head & 0x7fffffffu);
    k += 2;
    for (RemoteLink& l : plan.links) {
      const uint32_t packed = word(k + 2);
      l = {word(k), word(k + 1), uint16_t(packed & 0xffffu), uint8_t((packed >> 16) & 0xffu), uint8_t(packed >> 24)};
      k += 3;
    }
    plan_of[receiver] = uint32_t(plans.size());
    plans.push_back(std::move(plan));
  }
}

namespace {

// A link as much as the refinement reads of one it splits or casts again.
Link as_link(const RemoteLink& r) {
  Link l;
  l.source = r.source;
  l.rays = r.rays;
  l.samples = r.samples;
  return l;
}

}  // namespace

std::vector<std::vector<uint32_t>> Solver::remote_candidates(uint32_t i, const RemotePlan& plan) const {
  std::vector<std::vector<uint32_t>> out(plan.links.size());
  for (size_t k = 0; k < plan.links.size(); ++k)
    if (plan.links[k].action == kSplit) out[k] = link_candidates(i, as_link(plan.links[k]));
  return out;
}

void Solver::apply_plan(uint32_t i, const RemotePlan& plan, std::vector<std::vector<uint32_t>>& candidates) {
  std::vector<Link> links;
  if (here(i)) {
    links = std::move(h_[i].links);
    h_[i].links.clear();
  }
  if (plan.split_receiver) {
    ++stats_.refinements;
    ++stats_.receiver_splits;
  }
  if (!links.empty()) {  // the kept links stay where they are held (refine adds none to i itself)
    h_[i].links.reserve(links.size() - plan.links.size());
    size_t next = 0;
    for (size_t k = 0; k < links.size(); ++k) {
      if (next < plan.links.size() && plan.links[next].index == k) ++next;
      else h_[i].links.push_back(links[k]);
    }
    std::vector<Link>().swap(links);
  }
  for (size_t k = 0; k < plan.links.size(); ++k) {
    const Link l = as_link(plan.links[k]);
    if (plan.links[k].action == kRecast) recast(i, l);
    else replace_link(i, l, plan.split_receiver, candidates[k]);
  }
}

void Solver::evaluate_divided(IterationStats& is) {
  take_requests();
  // The cluster receivers' links (on every rank) apart from this rank's receivers'.
  PendingList shared;
  size_t kept = 0;
  for (size_t k = 0; k < pending_.size(); ++k) {
    if (h_[pending_[k].receiver].cluster) shared.push_back(pending_[k]);
    else pending_[kept++] = pending_[k];
  }
  pending_.erase(pending_.begin() + std::ptrdiff_t(kept), pending_.end());
  const auto start = std::chrono::steady_clock::now();
  evaluator_.evaluate_range(pending_, 0, pending_.size());
  rank_work().compute_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rank_work().items += pending_.size();
  rank_work().links += pending_.size();
  for (const Pending& p : pending_) rank_work().rays += p.rays;
  const std::vector<size_t> blocks =
      run_my_block(shared.size(), [&](size_t k) { return 1.0 + shared[k].samples; }, [&](size_t begin, size_t end) {
        evaluator_.evaluate_range(shared, begin, end);
        rank_work().links += end - begin;
        for (size_t k = begin; k < end; ++k) rank_work().rays += shared[k].rays;
      });
  share_blocks(shared, blocks);
  // What the links count: this rank's summed over the ranks (integers: any order), the clusters' as
  // every rank has them.
  LinkCounts counts = count_links(pending_);
  all_sum(counts.data(), counts.size());
  const LinkCounts clusters = count_links(shared);
  for (size_t k = 0; k < counts.size(); ++k) counts[k] += clusters[k];
  add_counts(counts, is);
  store_links(shared);
  store_links(pending_);
  PendingList().swap(pending_);
  elsewhere_ = 0;
}

void Solver::share_gathered() {
  struct Gathered {
    Vec3 H, Hp;
    double Fsum, Fp;
  };
  share_element_values<Gathered>(
      h_, [&](uint32_t i) { const HNode& n = h_[i]; return Gathered{n.H, n.Hp, n.Fsum, n.Fp}; },
      [&](uint32_t i, const Gathered& g) {
        HNode& n = h_[i];
        n.H = g.H;
        n.Hp = g.Hp;
        n.Fsum = g.Fsum;
        n.Fp = g.Fp;
      });
}

void Solver::shoot_importance_exactly() {
  HNodes& nodes = h_.nodes();
  // Each link's importance ρ_i F_ij I_i to its source, in units of 2^-k of a bound on the total (the
  // sum of their sizes, node by node in order: the same bound on every rank), as integers.
  // Cluster receivers' links are on every rank: rank 0 adds them (counts_links).
  std::vector<double> size(nodes.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const HNode& n = nodes[i];
      double sum = 0;
      for (const Link& l : n.links) sum += std::fabs(luminance(n.rho) * l.F * n.I);
      size[i] = sum;
    }
  });
  share_element_values(h_, size);
  double bound = 0;
  for (double v : size) bound += v;
  std::vector<double>().swap(size);
  for (HNode& n : nodes) n.Ig = 0;
  if (!(bound > 0) || !std::isfinite(bound)) return;
  // |Σ| < 2^60 + a half-unit a link: far inside 64 bits.
  const double unit = std::ldexp(1.0, 60 - (std::ilogb(bound) + 1));
  std::vector<int64_t> sum(nodes.size(), 0);
  for (uint32_t i = 0; i < nodes.size(); ++i)  // sequential: no two threads add to one source
    if (counts_links(h_, i))
      for (const Link& l : nodes[i].links)
        for_each_part(h_, l, [&](uint32_t part, double w) {
          sum[part] += std::llround(luminance(nodes[i].rho) * l.F * nodes[i].I * w * unit);
        });
  if (divided_) all_sum(sum.data(), sum.size());
  const double back = 1.0 / unit;  // a power of 2: exact
  for (size_t k = 0; k < nodes.size(); ++k) nodes[k].Ig = double(sum[k]) * back;
}

void Solver::note_link_memory() {
  const uint64_t bytes = requests_.capacity() * sizeof(LinkRequest) + pending_.capacity() * sizeof(Pending) + link_bytes(h_);
  stats_.link_bytes_peak = std::max(stats_.link_bytes_peak, bytes);
  rank_work().link_bytes_peak = std::max(rank_work().link_bytes_peak, bytes);
}

}  // namespace walkrad::hierarchical_detail
