// The refinement as a divided solve runs it (refinement.h, division.h, docs/scaling.md): each rank makes
// the plans of the receivers whose links it keeps and sends them to the others; every rank applies every
// plan, in one order, so that the nodes and the new links' count are the same on every rank. With
// Jacobi sweeps the same steps run in one process (Division::divisible), so that a bake over N ranks
// is the bake of one.
#include "refinement.h"

#include <algorithm>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/core/ranks.h"

namespace walkrad::hierarchical_detail {

void Refinement::exchange_plans(std::vector<uint32_t>& plan_of, std::vector<RemotePlan>& plans) const {
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
  const std::vector<uint8_t> all = division_.divided ? all_gather(mine) : std::move(mine);
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

std::vector<std::vector<uint32_t>> Refinement::remote_candidates(uint32_t i, const RemotePlan& plan) const {
  std::vector<std::vector<uint32_t>> out(plan.links.size());
  for (size_t k = 0; k < plan.links.size(); ++k)
    if (plan.links[k].action == kSplit) out[k] = link_candidates(i, as_link(plan.links[k]));
  return out;
}

void Refinement::apply_plan(uint32_t i, const RemotePlan& plan, std::vector<std::vector<uint32_t>>& candidates) {
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

}  // namespace walkrad::hierarchical_detail
