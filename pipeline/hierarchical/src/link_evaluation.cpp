// Form factors of links (link_evaluator.h), in parallel: the contour formula over receiver quadrature
// points with a control variate for visibility (elements), Monte Carlo point pairs (clusters), the
// extinction grid where volumes stand in.
#include "link_evaluator.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/core/invariant.h"
#include "walkrad/core/rounding.h"
#include "walkrad/hierarchical/transmission.h"
#include "walkrad/core/sampling.h"
#include "walkrad/formfactor/form_factor.h"

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

// Scratch of one thread's links (evaluate takes its lists from the caller; these are the evaluation's own).
thread_local std::vector<uint8_t> blocked_scratch;
thread_local std::vector<double> kernel_scratch;
thread_local std::vector<uint8_t> quadrant_scratch;

}  // namespace

bool luminaire(const Hierarchy& h, const HierarchicalSettings& s, const HNode& n) {
  return !n.cluster &&
         (max_component(n.emission) > 0 || (simulated_lights(s) && max_component(simulated_transmittance(h, s, n)) > 0));
}

bool close_pair(const Hierarchy& h, uint32_t i, uint32_t j) {
  const double reach = std::max(h[i].cluster ? h[i].radius : 0.0, h[j].cluster ? h[j].radius : 0.0);
  return reach > 0 && clearly_greater(0.5 * reach, box_distance(h[i].bounds, h[j].bounds));
}

LinkEvaluator::LinkEvaluator(const Hierarchy& h, const RayScene& rays, const HierarchicalSettings& s)
    : h_(h), rays_(rays), proof_(h.scene(), h.tree()), s_(s) {}

void LinkEvaluator::evaluate_range(PendingList& list, size_t begin, size_t end) const {
  tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, 64), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<RayScene::Segment> segments;
    std::vector<double> visible, weights;
    for (size_t k = r.begin(); k != r.end(); ++k) {
      evaluate(list[k], segments, visible, weights);
      WALKRAD_INVARIANT(std::isfinite(list[k].F) && list[k].F >= 0 && std::isfinite(list[k].sigma) && list[k].sigma >= 0,
                        "link " + std::to_string(list[k].receiver) + " <- " + std::to_string(list[k].source) + ": F " +
                            std::to_string(list[k].F) + ", sigma " + std::to_string(list[k].sigma));
    }
  });
}

void LinkEvaluator::visibility(Pending& p, const std::vector<RayScene::Segment>& segments, std::vector<double>& visible) const {
  visible.assign(segments.size(), 1.0);
  if (segments.empty()) return;
  if (p.need_rays) {
    std::vector<uint8_t>& blocked = blocked_scratch;
    blocked.assign(segments.size(), 0);
    (p.volume ? *s_.volumes->solid : rays_).occluded(segments.data(), segments.size(), blocked.data());
    p.rays = segments.size();
    if (s_.ray_sample && !p.volume) {
      const uint64_t hash = (uint64_t(p.receiver) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(p.source) * 0xC2B2AE3D27D4EB4Full);
      if ((hash >> 32) % std::max<uint32_t>(s_.ray_sample->every, 1) == 0) {
        const std::lock_guard<std::mutex> hold(s_.ray_sample->lock);
        s_.ray_sample->link_begin.push_back(s_.ray_sample->segments.size());
        s_.ray_sample->segments.insert(s_.ray_sample->segments.end(), segments.begin(), segments.end());
      }
    }
    for (size_t k = 0; k < segments.size(); ++k)
      if (blocked[k]) visible[k] = 0.0;
  }
  if (p.volume) {
    for (size_t k = 0; k < segments.size(); ++k)
      if (visible[k] > 0) visible[k] *= s_.volumes->grid->transmittance(segments[k].from, segments[k].to);
    p.grid_segments = segments.size();
  }
  // Clear glass on the way (a link carries one form factor: the panes' transmittance by luminance,
  // exact for neutral glass). Not in the shafts' candidates, so asked of every segment.
  if (rays_.has_glass())
    for (size_t k = 0; k < segments.size(); ++k)
      if (visible[k] > 0) visible[k] *= luminance(rays_.transmittance(segments[k].from, segments[k].to));
}

namespace {

// What a link's samples say of each receiver child beyond their noise: the child's estimate F_c
// against the whole link's F, its deviation shrunk by two standard errors (so that a uniform
// transfer is not taken for an uneven one), as a share of F (Link::share).
std::array<float, 4> shares(const double* Fc, const double* sigma_c, uint32_t count, double F) {
  std::array<float, 4> out = {1, 1, 1, 1};
  if (F <= 0) return out;
  for (uint32_t c = 0; c < count; ++c) {
    const double d = Fc[c] - F, kept = std::max(0.0, std::fabs(d) - 2.0 * sigma_c[c]);
    out[c] = float(1.0 + std::copysign(kept, d) / F);
  }
  return out;
}

// Whether every point of the box lies behind the plane through x of normal n, by a margin far past
// rounding: then a cosine at x towards any of them is negative, whatever point is drawn there. Four in
// five of office3's cluster samples face away (126.8 M drawn, 25.5 M facing); the receiver's point
// decides for many of them before the source's is drawn.
bool box_behind(const Vec3& x, const Vec3& n, const Bounds& b) {
  const Vec3 c = b.center(), h = b.diagonal() * 0.5;
  const double reach = std::fabs(n.x) * h.x + std::fabs(n.y) * h.y + std::fabs(n.z) * h.z;
  const double scale = length(h) + std::max({std::fabs(x.x), std::fabs(x.y), std::fabs(x.z), std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
  return dot(n, c - x) + reach < -1e-9 * scale;
}

// Each of an element's quadrants (split_element) as a share of its area (Link::seen's baseline).
void quadrant_area_shares(const Polygon& shape, double area, double* share) {
  const std::array<Polygon, 4> parts = split_element(shape);
  for (int c = 0; c < 4; ++c) share[c] = polygon_area(parts[size_t(c)]) / area;
}

}  // namespace

void LinkEvaluator::evaluate_elements(Pending& p, Rng& rng, std::vector<RayScene::Segment>& segments,
                               std::vector<double>& visible) const {
  // Element to element, quadrant by quadrant of the receiver (its children to be, split_element):
  // the contour formula over each quadrant's quadrature points gives its unoccluded form factor
  // exactly; rays from points uniform over the quadrant to points uniform over the source estimate
  // the part hidden, (A_j/π) E[cos cos / r² · blocked] (a control variate: unbiased, where a
  // visible fraction of rays is biased near occluders). F is the quadrants' area mean.
  // A link whose every ray is blocked sees nothing of the source: 0, not the control variate's
  // unbiased but noisy difference, which is positive half of the time and leaked light into closed
  // rooms (stability suite, junctions). Through volumes no ray is ever wholly blocked
  // (transmittance exp(−τ) > 0): where most of the source is hidden the control variate is all
  // noise, so the plain estimate of the part that arrives, (A_j/π) E[cos cos / r² · visible], is
  // used instead (unbiased as well).
  const HNode& ri = h_[p.receiver];
  const HNode& sj = h_[p.source];
  const double offset = rays_.offset();
  const std::array<Polygon, 4> kids = split_element(ri.shape);
  // Each end's size: the side of its area, or half its longest side where that is longer (an element
  // more elongated than 4 to 1: a corridor's floor, 160 × 2 m, is 80 m long to a lamp at its one end,
  // not 18; one point a quadrant put its first 20 m from the doorway).
  auto size = [](const HNode& n) {
    double longest = 0;
    for (int k = 0; k < n.shape.count; ++k) longest = std::max(longest, length(n.shape.v[size_t((k + 1) % n.shape.count)] - n.shape.v[size_t(k)]));
    return std::max(std::sqrt(n.area), 0.5 * longest);
  };
  const int order = std::max(1, quadrature_order(length(ri.center - sj.center), size(ri), size(sj)) / 2);
  const int per_child = p.need_rays || p.volume ? std::max(1, p.samples / 4) : 0;
  std::vector<double>& kernel = kernel_scratch;
  kernel.clear();
  std::vector<uint8_t>& quadrant = quadrant_scratch;  // of each sample's source point
  quadrant.clear();
  segments.clear();
  double area[4], unoccluded[4];
  double seen[4] = {0, 0, 0, 0};  // the visible kernel by the source's quadrant (Link::seen)
  double inner = 0;               // Link::inner, as a share of a child's kernel
  // Only the luminaires' links are read for it (measure_variation); even orders split into quarters.
  const bool quarters = luminaire(h_, s_, sj) && order >= 2 && order % 2 == 0;
  const ContourSource contour(sj.shape);
  for (int c = 0; c < 4; ++c) {
    area[c] = polygon_area(kids[c]);
    unoccluded[c] = 0;
    // The points come row by row (quadrature_points): with an even order each quarter of the child
    // holds (order/2)² of them, whose mean against the child's is Link::inner.
    double quarter[4] = {0, 0, 0, 0}, quarter_w[4] = {0, 0, 0, 0};
    int point = 0;
    for (const QuadraturePoint& q : quadrature_points(kids[c], order)) {
      const int part = (point / order >= order / 2 ? 2 : 0) + (point % order >= order / 2 ? 1 : 0);
      ++point;
      quarter_w[part] += q.weight;
      if (dot(q.position - sj.shape.v[0], sj.normal) <= 0) continue;
      const double f = q.weight * point_to_polygon(q.position, ri.normal, contour);
      unoccluded[c] += f;
      quarter[part] += f;
    }
    if (quarters && unoccluded[c] > 0 && area[c] > 0)
      for (int part = 0; part < 4; ++part)
        if (quarter_w[part] > 0)
          inner = std::max(inner, std::fabs(quarter[part] / quarter_w[part] - unoccluded[c] / area[c]));
    for (int k = 0; k < per_child; ++k) {
      // Named: the order of arguments' evaluation is unspecified (the order GCC took is kept).
      const double xv = rng.uniform(), xu = rng.uniform();
      const Vec3 x = sample_polygon(kids[c], xu, xv);
      const double v = rng.uniform(), u = rng.uniform();
      const Vec3 y = sample_polygon(sj.shape, u, v);
      segments.push_back({x + ri.normal * offset, y + sj.normal * offset});
      kernel.push_back(sj.area / kPi * point_kernel(x, ri.normal, y, sj.normal));
      quadrant.push_back(uint8_t(sample_quadrant(sj.shape, u, v)));
    }
  }
  visibility(p, segments, visible);
  double Fc[4], sigma_c[4], F = 0, arrives = 0, hidden_part = 0, variance = 0;
  size_t hidden = 0;
  for (int c = 0; c < 4; ++c) {
    double occluded = 0, occluded2 = 0, open = 0;
    for (int k = 0; k < per_child; ++k) {
      const double v = visible[size_t(c * per_child + k)], K = kernel[size_t(c * per_child + k)];
      occluded += K * (1.0 - v);
      occluded2 += K * K * (1.0 - v) * (1.0 - v);
      open += K * v;
      seen[quadrant[size_t(c * per_child + k)]] += area[c] * K * v;  // each receiver quadrant by its area
      hidden += v == 0.0;
    }
    const double n = double(std::max(1, per_child));
    const double mean = occluded / n, var = per_child > 1 ? std::max(0.0, occluded2 / n - mean * mean) / (n - 1) : 0.0;
    Fc[c] = (area[c] > 0 ? unoccluded[c] / area[c] : 0.0) - mean;
    sigma_c[c] = std::sqrt(var);
    const double w = area[c] / ri.area;
    F += w * Fc[c];
    variance += w * w * var;
    arrives += w * open / n;
    hidden_part += w * mean;
  }
  if (p.volume && arrives < hidden_part) F = arrives;
  p.F = std::max(0.0, F);
  p.sigma = std::sqrt(variance);
  double open = 0;
  for (int c = 0; c < 4; ++c) open += unoccluded[c];
  p.open = float(open / ri.area);
  if (!segments.empty() && hidden == segments.size()) {
    // Every ray blocked: 0, and nothing at all where the occlusion is proven; else the part n rays
    // could have missed stays uncertain (a visible fraction of about 1/n), so that the refinement can
    // still find the part that sees.
    p.F = 0;
    p.proven = proven_hidden(p, segments);
    p.sigma = p.proven ? 0.0f : p.open / float(segments.size());
  }
  p.share = shares(Fc, sigma_c, 4, p.F);
  p.inner = p.F > 0 ? uint8_t(std::min(255.0, std::round(64.0 * inner / p.F))) : 0;
  if (per_child > 0 && p.F > 0) {  // where rays were cast
    double area_share[4];
    quadrant_area_shares(sj.shape, sj.area, area_share);
    p.seen = seen_weights(seen, area_share, 4, s_.error);
  }
}

void LinkEvaluator::evaluate(Pending& p, std::vector<RayScene::Segment>& segments, std::vector<double>& visible,
              std::vector<double>& weights) const {
  WALKRAD_INVARIANT(p.receiver < h_.nodes().size() && p.source < h_.nodes().size() && p.receiver != p.source,
                    "a link between nodes " + std::to_string(p.receiver) + " and " + std::to_string(p.source));
  const HNode& ri = h_[p.receiver];
  const HNode& sj = h_[p.source];
  Rng rng(p.receiver, p.source);
  const double offset = rays_.offset();
  segments.clear();
  weights.clear();
  if (!ri.cluster && !sj.cluster) {
    evaluate_elements(p, rng, segments, visible);
    return;
  }
  // A cluster at one end or both (Smits, Arvo & Greenberg 1994): the unoccluded form factor from
  // the receiver's surfaces to the source's, exactly (element to element over every pair of
  // polygons) when they hold few, else by Monte Carlo over area-sampled point pairs with each
  // surface's own cosine; visibility as the kernel-weighted fraction of rays that arrive.
  // Between clusters of mostly unrelated orientations few pairs face each other: keep drawing (up
  // to 8n) until a quarter of n did, or the visibility fraction would rest on one or no sample
  // (and be 0 for a link whose unoccluded form factor is known to be positive).
  const int n = std::max(1, p.samples);
  // A close pair left whole (close_matters): each sample stands for a disc of 1/n of the source's
  // area, whose form factor A/(πr² + A) is bounded where 1/r² is not (Wallace, Elmquist & Haines
  // 1989). Between touching books the point kernel's tail made rows sum past 1.
  const double disc = close_pair(h_, p.receiver, p.source) ? sj.area / n : 0.0;
  double mc = 0, weighted = 0, open = 0;
  int drawn = 0, facing = 0;
  thread_local std::vector<ClusterSample> drawn_samples;
  drawn_samples.clear();
  for (; drawn < n || (facing < (n + 3) / 4 && drawn < 8 * n); ++drawn) {
    Vec3 pi, ni, pj, nj;
    uint32_t child = 0;
    // Named: the order of arguments' evaluation is unspecified (the order GCC took is kept).
    const double rw = rng.uniform(), rv = rng.uniform(), ru = rng.uniform();
    h_.sample(ri, ru, rv, rw, pi, ni, &child);
    uint32_t source_child = 0;
    const double sw = rng.uniform(), sv = rng.uniform(), su = rng.uniform();
    if (!ri.cluster) child = sample_quadrant(ri.shape, ru, rv);  // an element receiver's child to be
    if (box_behind(pi, ni, sj.bounds)) {  // no point of the source can face this one: no need to draw it
      drawn_samples.push_back({child, 0, 0.0, -1});
      continue;
    }
    h_.sample(sj, su, sv, sw, pj, nj, &source_child);
    if (!sj.cluster) source_child = sample_quadrant(sj.shape, su, sv);
    drawn_samples.push_back({child, source_child, 0.0, -1});
    const Vec3 d = pj - pi;
    const double r2 = dot(d, d);
    if (r2 <= 0) continue;
    const Vec3 u = d / std::sqrt(r2);
    const double ci = dot(ni, u), cj = -dot(nj, u);
    if (ci <= 0 || cj <= 0) continue;
    const double kernel = ci * cj * sj.area / (kPi * r2 + disc);  // finite: linked clusters do not overlap
    mc += kernel;
    ++facing;
    drawn_samples.back().value = kernel;
    if (p.need_rays || p.volume) {
      drawn_samples.back().segment = int32_t(segments.size());
      segments.push_back({pi + ni * offset, pj + nj * offset});
      weights.push_back(kernel);
    }
  }
  visibility(p, segments, visible);
  double open2 = 0, shut2 = 0;
  for (size_t k = 0; k < segments.size(); ++k) {
    weighted += weights[k];
    open += weights[k] * visible[k];
    shut2 += weights[k] * weights[k] * (1 - visible[k]) * (1 - visible[k]);
  }
  for (const ClusterSample& c : drawn_samples) {
    const double v = c.segment >= 0 ? c.value * visible[size_t(c.segment)] : c.value;
    open2 += v * v;
  }
  // F = unoccluded − occluded part. The unoccluded form factor is exact for few polygon pairs and
  // the Monte Carlo mean otherwise; the occluded part, (1/N) Σ K · blocked, is an unbiased estimate
  // from the same samples (a control variate: no ratio, so no bias from few facing samples).
  const double N = drawn;
  const double occluded = (weighted - open) / N;
  // Every ray blocked, F is 0 and the unoccluded factor only scales σ (what the rays could have
  // missed): the samples' mean serves, not the exact sum over up to 64 polygon pairs (44% of the
  // exact sums on office-floor's 32 rooms, their pairs 45%).
  const bool all_blocked = !segments.empty() && open == 0;
  const bool exact = !all_blocked && polygon_pairs(ri, sj) <= kExactClusterPairs;
  const double unoccluded = exact ? exact_unoccluded(ri, sj) : mc / N;
  // Mostly hidden through volumes: the plain estimate, as for elements above.
  const bool mostly_hidden = p.volume && open < weighted - open;
  const bool plain = mostly_hidden || !exact;  // the estimate is the mean of K·v over the samples
  // Not capped above (a cap at min(1, A_j/A_i) would bias the estimate low); rows that sum to too
  // much are caught at the leaves (push_pull). Every ray blocked: 0 (as for elements above).
  p.F = all_blocked ? 0.0 : std::max(0.0, mostly_hidden ? open / N : unoccluded - occluded);
  p.proven = all_blocked && proven_hidden(p, segments);
  // Standard error: of the mean of K·v, or of the hidden part's mean K·(1 − v) beside an exact F;
  // every ray blocked: a visible fraction of about 1/n of the unoccluded form factor.
  const double m = plain ? open / N : occluded, m2 = plain ? open2 / N : shut2 / N;
  p.open = float(unoccluded);
  p.sigma = p.proven ? 0.0 : all_blocked ? unoccluded / double(segments.size())
                        : N > 1 ? std::sqrt(std::max(0.0, m2 - m * m) / (N - 1)) : 0.0;
  p.share = ri.cluster ? cluster_shares(ri, sj) : child_shares(4, drawn_samples, visible, open / N);
  // Link::seen, where rays were cast: the visible kernel of the samples by the source's part.
  const uint32_t source_kids = sj.cluster ? sj.child_count : 4;
  if (!segments.empty() && open > 0 && p.F > 0 && source_kids >= 2 && source_kids <= 4) {
    double seen[4] = {0, 0, 0, 0};
    for (const ClusterSample& c : drawn_samples)
      if (c.segment >= 0) seen[c.source_child] += c.value * visible[size_t(c.segment)];
    double area_share[4];
    if (sj.cluster) {
      for (uint32_t c = 0; c < source_kids; ++c) area_share[c] = h_[h_.child(sj, c)].area / sj.area;
    } else {
      quadrant_area_shares(sj.shape, sj.area, area_share);
    }
    p.seen = seen_weights(seen, area_share, source_kids, s_.error);
  }
}

std::array<float, 4> LinkEvaluator::cluster_shares(const HNode& ri, const HNode& sj) const {
  // Each child's projected area towards the source, by the source's projected area towards it, over
  // the squared distance: what the child gets per unit area, against the cluster's area mean. From
  // geometry alone (a few Monte Carlo samples per child could not tell a book's spine from its top).
  std::array<float, 4> out = {1, 1, 1, 1};
  const uint32_t kids = ri.child_count;
  if (kids < 2 || kids > 4) return out;
  double k[4] = {}, mean = 0;
  for (uint32_t c = 0; c < kids; ++c) {
    const HNode& n = h_[h_.child(ri, c)];
    const Vec3 d = sj.center - n.center;
    const double r = std::max(length(d), 1e-30);
    const Vec3 u = d / r;
    const double towards = sj.cluster ? projected_area(sj, -u) / std::max(sj.area, 1e-300) : std::max(0.0, -dot(sj.normal, u));
    k[c] = (n.area > 0 ? projected_area(n, u) / n.area : 0.0) * towards / (r * r + sj.radius * sj.radius);
    mean += k[c] * n.area / ri.area;
  }
  if (mean <= 0) return out;
  for (uint32_t c = 0; c < kids; ++c) out[c] = float(k[c] / mean);
  return out;
}

std::array<float, 4> LinkEvaluator::child_shares(uint32_t children, const std::vector<ClusterSample>& samples,
                                          const std::vector<double>& visible, double F) {
  double Fc[4] = {}, sigma_c[4] = {};
  if (children < 2 || children > 4 || samples.empty()) return shares(Fc, sigma_c, 0, F);
  double sum[4] = {}, sq[4] = {}, count[4] = {};
  for (const ClusterSample& s : samples) {
    const double v = s.segment >= 0 ? s.value * visible[size_t(s.segment)] : s.value;
    sum[s.child] += v;
    sq[s.child] += v * v;
    count[s.child] += 1;
  }
  for (uint32_t c = 0; c < children; ++c) {
    if (count[c] < 2) {  // too few samples to say anything of this child
      Fc[c] = F;
      continue;
    }
    Fc[c] = sum[c] / count[c];
    sigma_c[c] = std::sqrt(std::max(0.0, sq[c] / count[c] - Fc[c] * Fc[c]) / (count[c] - 1));
  }
  return shares(Fc, sigma_c, children, F);
}

double LinkEvaluator::point_kernel(const Vec3& x, const Vec3& nx, const Vec3& y, const Vec3& ny) {
  const Vec3 d = y - x;
  const double r2 = dot(d, d);
  if (r2 <= 0) return 0;
  return std::max(0.0, dot(nx, d)) * std::max(0.0, -dot(ny, d)) / (r2 * r2);
}

}  // namespace walkrad::hierarchical_detail
