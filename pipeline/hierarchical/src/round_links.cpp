// The round's links as the solver handles them around their evaluation (link_evaluator.h): the
// refinement's requests made into pending links, evaluated (divided among ranks under mpirun), counted
// into the statistics and stored at their receivers.
#include "solver.h"

#include <algorithm>
#include <chrono>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/core/ranks.h"

namespace walkrad::hierarchical_detail {

void Solver::take_requests() {
  std::vector<LinkRequest> requests = refinement_.take_requests();
  if (s_.check_limits) s_.check_limits("link evaluation", requests.size() * sizeof(Pending));
  pending_.reserve(requests.size());
  for (const LinkRequest& r : requests) pending_.emplace_back(r);
  note_link_memory(requests.capacity() * sizeof(LinkRequest));  // both lists held: the round's peak
}

void Solver::evaluate_pending(IterationStats& is) {
  if (division_.divided) {
    evaluate_divided(is);
    return;
  }
  take_requests();
  // Under mpirun each rank evaluates one contiguous block of the round's links, of about equal cost
  // (rays or samples, plus one), and every rank gathers every block (ranks.h): the links and their
  // order are the same on every rank, and so is each link's result.
  const std::vector<size_t> blocks =
      run_my_block(pending_.size(), [&](size_t k) { return 1.0 + pending_[k].samples; }, [&](size_t begin, size_t end) {
        evaluator_.evaluate_range(pending_, begin, end);
        rank_work().links += end - begin;
        for (size_t k = begin; k < end; ++k) rank_work().rays += pending_[k].rays;
      });
  share_blocks(pending_, blocks);  // each link whole: its two ends are the same on every rank
  add_counts(count_links(pending_), is);
  store_links(pending_);
  PendingList().swap(pending_);  // its capacity too: the largest round's list is not kept
}

Solver::LinkCounts Solver::count_links(const PendingList& list) const {
  LinkCounts c{};
  for (const Pending& p : list) {
    c[kRays] += p.rays;
    ++c[p.volume ? kVolume : p.need_rays ? kExact : kUnoccluded];
    if (p.volume) c[kGridSegments] += p.grid_segments;
    c[kMonteCarlo] += h_[p.receiver].cluster || h_[p.source].cluster;
    c[kKept] += kept(p);
    c[kProven] += p.proven;
  }
  return c;
}

void Solver::add_counts(const LinkCounts& c, IterationStats& is) {
  for (uint64_t* rays : {&stats_.rays, &is.rays}) *rays += uint64_t(c[kRays]);
  stats_.volume_links += uint64_t(c[kVolume]);
  stats_.grid_segments += uint64_t(c[kGridSegments]);
  stats_.exact_links += uint64_t(c[kExact]);
  stats_.unoccluded_links += uint64_t(c[kUnoccluded]);
  stats_.monte_carlo_links += uint64_t(c[kMonteCarlo]);
  stats_.links += uint64_t(c[kKept]);
  stats_.proven_hidden += uint64_t(c[kProven]);
}

void Solver::store_links(PendingList& list) {
  // The shares scaled to their area mean first, each link on its own (in parallel): 1.2 s of one
  // thread at 150 rooms, the receivers' quadrants cut again for every link.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, list.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k != r.end(); ++k)
      if (kept(list[k])) normalize_shares(h_, list[k].receiver, list[k].share);
  });
  // Each receiver's list grows once, to its exact size: grown link by link, a list doubles and leaves
  // up to half of itself unused. The kept links
  // sorted by receiver first (a counting sort, in list order), so that the receivers fill their
  // lists on all threads, each in list order as one thread filled them.
  const size_t nodes = h_.nodes().size();
  std::vector<uint32_t> begin(nodes + 1, 0);
  for (const Pending& p : list)
    if (kept(p)) ++begin[p.receiver + 1];
  for (size_t i = 0; i < nodes; ++i) begin[i + 1] += begin[i];
  std::vector<uint32_t> order(begin[nodes]), next(begin.begin(), begin.end() - 1);
  for (size_t k = 0; k < list.size(); ++k)
    if (kept(list[k])) order[next[list[k].receiver]++] = uint32_t(k);
  std::vector<uint32_t>().swap(next);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes, 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      if (begin[i] == begin[i + 1]) continue;
      std::vector<Link>& links = h_[uint32_t(i)].links;
      links.reserve(links.size() + (begin[i + 1] - begin[i]));
      for (uint32_t k = begin[i]; k < begin[i + 1]; ++k) {
        const Pending& p = list[order[k]];
        Link l{float(p.F), p.source, p.sigma, p.open, p.share, uint8_t((p.need_rays ? 1 : 0) | (p.volume ? 2 : 0)), p.inner,
               uint16_t(std::min(p.samples, 65535))};
        l.seen = p.seen;
        links.push_back(l);
      }
    }
  });
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
}

void Solver::note_link_memory(uint64_t taken_requests) {
  const uint64_t bytes = refinement_.request_bytes() + taken_requests + pending_.capacity() * sizeof(Pending) + link_bytes(h_);
  stats_.link_bytes_peak = std::max(stats_.link_bytes_peak, bytes);
  rank_work().link_bytes_peak = std::max(rank_work().link_bytes_peak, bytes);
}

}  // namespace walkrad::hierarchical_detail
