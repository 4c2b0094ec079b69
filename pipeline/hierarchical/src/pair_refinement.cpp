// The refinement of pairs of nodes (Hanrahan, Salzman & Aupperle 1991; clusters: Smits, Arvo &
// Greenberg 1994), breadth first: a pair is dropped, linked, or one end is split and its children's
// pairs refined with the pair's candidate occluders (shaft.h: the children's shafts lie inside it).
// Each level's decisions are made in parallel and applied in order (refinement.h, refine_pairs): the
// 150-room level spent 58 s of its 307 s on one thread in the depth-first version's shaft tests.
#include "refinement.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/core/rounding.h"

namespace walkrad::hierarchical_detail {

namespace {

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

void Refinement::refine_first() {
  std::vector<PairTask> root;
  root.push_back({h_.root(), h_.root()});
  refine_pairs(std::move(root));
}

Refinement::PairOutcome Refinement::decide_pair(PairTask& t) const {
  PairOutcome out;
  const uint32_t i = t.i, j = t.j;
  if (i == j) {
    if (h_[i].cluster) out.kind = PairKind::kSelf;  // a planar element does not see itself
    return out;
  }
  {
    const HNode& ri = h_[i];
    const HNode& sj = h_[j];
    if (!ri.cluster && !sj.cluster && ri.polygon == sj.polygon) return out;  // coplanar
    if (!ri.cluster && behind(ri, sj)) return out;
    if (!sj.cluster && behind(sj, ri)) return out;
  }
  // A cluster is linked only from far enough away (close_pair): closer, a surface of the cluster may
  // lie centimetres from the other end (a bookcase against a wall), where the point-sampled kernel
  // 1/r² has huge variance and the cluster's average radiosity says nothing of that surface. Where the
  // walkthrough does not look the pair stays whole (close_matters; its kernel bounded: evaluate; its
  // receivers' rows left unscaled: under_close_pairs).
  const bool must_split = (close_pair(h_, i, j) && close_matters(i)) || two_sided(i) || two_sided(j);

  // Candidates between the two: the parent's list filtered by this pair's shaft.
  const Shaft shaft(h_[i].bounds, h_[j].bounds);
  const uint32_t ex_i = h_[i].cluster ? UINT32_MAX : h_[i].polygon, ex_j = h_[j].cluster ? UINT32_MAX : h_[j].polygon;
  // With compact lists from a parent, the list itself is built only for a pair that splits again, and
  // each count is a pass over the parent's list: a pair is counted only as far as its decision needs
  // (worth_splitting asks only whether something can block, and asks nothing more of a pair that splits
  // either way, since an occluded pair is worth splitting wherever an unoccluded one is); a link needs
  // its count up to the thresholds below.
  const bool lazy = compact() && t.parent;
  const bool si = splittable(i), sj = splittable(j);
  std::vector<uint32_t> candidates;
  size_t listed = 0;
  bool split = false;
  auto count = [&](size_t limit) { return count_compact_candidates(h_.tree(), shaft, *t.parent, ex_i, ex_j, limit); };
  if (!lazy) {
    candidates = t.has_own ? std::move(t.own) : occluders(i, j, shaft, ex_i, ex_j, t.parent);
    listed = compact() ? candidate_count(h_.tree(), candidates, ex_i, ex_j) : candidates.size();
    split = t.force || must_split || oracle_.worth_splitting(i, j, listed > 0);
  } else if ((si || sj) && (t.force || must_split || oracle_.worth_splitting(i, j, false))) {
    split = true;
  } else if ((si || sj) && oracle_.worth_splitting(i, j, true) && count(1) > 0) {
    split = true;
  } else {
    listed = count(kManyBlockers + 1);
  }

  // A pair whose parent's list is long (rooms apart: the 150-room level's third round filtered 3.9 G
  // entries for pairs 30 m apart or more, half that round's CPU) is probed with a few rays before its
  // list is filtered: where every one is blocked it is linked, with the rays of a recast (hidden, it is
  // settled at once), not split into thousands of pairs whose rays each find the same wall.
  if (split && lazy && !t.force && !must_split && t.parent->size() > s_.probe_entries) {
    probe(i, j, out);
    if (out.probe_hidden) {
      out.kind = PairKind::kLink;
      out.samples = kHiddenRecast * s_.rays;
      out.need_rays = true;
      return out;
    }
  }
  if (split) {
    if (si || sj) {
      bool split_receiver = si && (!sj || !clearly_greater(h_[j].radius, h_[i].radius));
      if (must_split && si && sj && h_[i].cluster != h_[j].cluster) split_receiver = h_[i].cluster;
      if (must_split && !(split_receiver ? h_[i].cluster : h_[j].cluster) && (split_receiver ? sj : si) &&
          (split_receiver ? h_[j].cluster : h_[i].cluster))
        split_receiver = !split_receiver;  // split the cluster end first
      out.kind = PairKind::kSplitEnd;
      out.split_receiver = split_receiver;
      out.candidates = lazy ? occluders(i, j, shaft, ex_i, ex_j, t.parent) : std::move(candidates);
      return out;
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
  out.kind = PairKind::kLink;
  out.samples = samples;
  out.need_rays = s_.visibility && blockers > size_t(volumes > 0);
  out.volume = s_.visibility && volumes > 0;
  return out;
}

void Refinement::probe(uint32_t i, uint32_t j, PairOutcome& out) const {
  const HNode& ri = h_[i];
  const HNode& sj = h_[j];
  Rng rng(j, i);  // not the link's own stream (evaluate: receiver, source)
  const double offset = rays_.offset();
  std::vector<RayScene::Segment>& segments = probe_scratch_;
  segments.clear();
  const int n = s_.rays;
  for (int drawn = 0; drawn < 4 * n && int(segments.size()) < n; ++drawn) {
    Vec3 pi, ni, pj, nj;
    const double rw = rng.uniform(), rv = rng.uniform(), ru = rng.uniform();
    h_.sample(ri, ru, rv, rw, pi, ni);
    const double sw = rng.uniform(), sv = rng.uniform(), su = rng.uniform();
    h_.sample(sj, su, sv, sw, pj, nj);
    const Vec3 d = pj - pi;
    if (dot(ni, d) <= 0 || dot(nj, d) >= 0) continue;
    segments.push_back({pi + ni * offset, pj + nj * offset});
  }
  if (segments.empty()) return;  // nothing faces: not hidden
  std::vector<uint8_t>& blocked = blocked_scratch_;
  blocked.assign(segments.size(), 0);
  rays_.occluded(segments.data(), segments.size(), blocked.data());
  out.probe_rays = uint32_t(segments.size());
  out.probe_hidden = std::all_of(blocked.begin(), blocked.end(), [](uint8_t b) { return b != 0; });
}

void Refinement::refine_pairs(std::vector<PairTask> tasks) {
  // The previous level's outcomes: their lists are what this level's pairs filter.
  std::vector<PairOutcome> parents;
  while (!tasks.empty()) {
    std::vector<PairOutcome> decided(tasks.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tasks.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t k = r.begin(); k != r.end(); ++k) decided[k] = decide_pair(tasks[k]);
    });
    // The next level's pairs, made to their count (at most: an element splits into 4): a list grown by
    // doubling is copied and faulted in about twice over.
    size_t more = 0;
    for (size_t k = 0; k < tasks.size(); ++k) {
      const PairOutcome& d = decided[k];
      const HNode& n = h_[d.kind == PairKind::kSplitEnd && !d.split_receiver ? tasks[k].j : tasks[k].i];
      if (d.kind == PairKind::kSelf) more += size_t(n.child_count) * n.child_count;
      else if (d.kind == PairKind::kSplitEnd) more += std::max<size_t>(n.child_count, 4);
    }
    std::vector<PairTask> next;
    next.reserve(more);
    for (size_t k = 0; k < tasks.size(); ++k) {
      const uint32_t i = tasks[k].i, j = tasks[k].j;
      PairOutcome& d = decided[k];
      stats_.probe_rays += d.probe_rays;
      stats_.probed_pairs += d.probe_rays > 0;
      stats_.probe_hidden += d.probe_hidden;
      if (d.kind == PairKind::kSelf) {
        // Its children's pairs filter its own list (a copy: the level it lies in is spent next).
        const std::vector<uint32_t>* list = nullptr;
        if (tasks[k].parent) list = &(d.candidates = *tasks[k].parent);
        const uint32_t count = h_[i].child_count;
        for (uint32_t a = 0; a < count; ++a)
          for (uint32_t b = 0; b < count; ++b) next.push_back({h_.child(h_[i], a), h_.child(h_[i], b), list});
      } else if (d.kind == PairKind::kSplitEnd) {
        const uint32_t end = d.split_receiver ? i : j;
        h_.subdivide(end);
        ++stats_.refinements;
        for (uint32_t c = 0; c < h_[end].child_count; ++c) {
          const uint32_t child = h_.child(h_[end], c);
          next.push_back({d.split_receiver ? child : i, d.split_receiver ? j : child, &d.candidates});
        }
      } else if (d.kind == PairKind::kLink) {
        // The list doubles when full: 2n entries allocated and filled while the n old ones are copied.
        if (s_.check_limits && requests_.size() == requests_.capacity() && requests_.size() >= 65536)
          s_.check_limits("refinement", 2 * requests_.capacity() * sizeof(LinkRequest));
        add_pending({i, j, d.samples, d.need_rays, d.volume});
      }
      if (d.kind == PairKind::kDrop || d.kind == PairKind::kLink) d = PairOutcome{};
    }
    // This level's lists are what the next filters; the previous level's are spent.
    std::vector<PairTask>().swap(tasks);
    tasks.swap(next);
    parents.swap(decided);
  }
}

}  // namespace walkrad::hierarchical_detail
