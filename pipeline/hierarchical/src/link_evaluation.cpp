// Form factors of links, in parallel: the contour formula over receiver quadrature points with a
// control variate for visibility (elements), Monte Carlo point pairs (clusters), the extinction grid
// where volumes stand in; and the punctual lights' direct irradiance of elements.
#include "solver.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/core/sampling.h"
#include "walkrad/formfactor/form_factor.h"

namespace walkrad::hierarchical_detail {

std::vector<double> Solver::direct_for(const std::vector<uint32_t>& elements) {
  std::vector<double> spread(elements.size(), 0.0);
  std::vector<uint64_t> rays(elements.size(), 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, elements.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k != r.end(); ++k) {
      HNode& n = h_[elements[k]];
      const DirectIrradiance d = direct_irradiance(n.shape, *s_.lights, s_.visibility ? &rays_ : nullptr, 4, rays[k]);
      n.D = d.mean;
      n.D_known = true;
      spread[k] = d.spread;
    }
  });
  for (uint64_t r : rays) stats_.light_rays += r;
  return spread;
}

void Solver::compute_missing_direct() {
  std::vector<uint32_t> missing;
  for (uint32_t i = 0; i < h_.nodes().size(); ++i)
    if (!h_[i].cluster && !h_[i].D_known) missing.push_back(i);
  direct_for(missing);
}

void Solver::evaluate_pending(IterationStats& is) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pending_.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<RayScene::Segment> segments;
    std::vector<double> visible;
    std::vector<double> weights;
    for (size_t k = r.begin(); k != r.end(); ++k) evaluate(pending_[k], segments, visible, weights);
  });
  for (const Pending& p : pending_) {
    stats_.rays += p.rays;
    is.rays += p.rays;
    if (p.volume) {
      ++stats_.volume_links;
      stats_.grid_segments += p.grid_segments;
    } else if (p.need_rays) {
      ++stats_.exact_links;
    } else {
      ++stats_.unoccluded_links;
    }
    if (h_[p.receiver].cluster || h_[p.source].cluster) ++stats_.monte_carlo_links;
    if (p.F > 0) {
      h_[p.receiver].links.push_back({p.source, p.F, p.spread});
      ++stats_.links;
    }
  }
  pending_.clear();
}

void Solver::visibility(Pending& p, const std::vector<RayScene::Segment>& segments, std::vector<double>& visible) const {
  visible.assign(segments.size(), 1.0);
  if (segments.empty()) return;
  if (p.need_rays) {
    std::vector<uint8_t>& blocked = blocked_scratch_;
    blocked.assign(segments.size(), 0);
    (p.volume ? *s_.volumes->solid : rays_).occluded(segments.data(), segments.size(), blocked.data());
    p.rays = segments.size();
    for (size_t k = 0; k < segments.size(); ++k)
      if (blocked[k]) visible[k] = 0.0;
  }
  if (p.volume) {
    for (size_t k = 0; k < segments.size(); ++k)
      if (visible[k] > 0) visible[k] *= s_.volumes->grid->transmittance(segments[k].from, segments[k].to);
    p.grid_segments = segments.size();
  }
}

void Solver::evaluate(Pending& p, std::vector<RayScene::Segment>& segments, std::vector<double>& visible,
              std::vector<double>& weights) const {
  const HNode& ri = h_[p.receiver];
  const HNode& sj = h_[p.source];
  Rng rng(p.receiver, p.source);
  const double offset = rays_.offset();
  segments.clear();
  weights.clear();
  if (!ri.cluster && !sj.cluster) {
    // Element to element: the contour formula over receiver quadrature points, each point's
    // visibility from rays to stratified points of the source.
    const int order = quadrature_order(length(ri.center - sj.center), std::sqrt(ri.area), std::sqrt(sj.area));
    const std::vector<QuadraturePoint> pts = quadrature_points(ri.shape, order);
    const int per_point = p.need_rays || p.volume ? std::max(1, p.samples / int(pts.size())) : 0;
    std::vector<double>& kernel = kernel_scratch_;
    kernel.clear();
    for (const QuadraturePoint& q : pts) {
      double f = 0;
      if (dot(q.position - sj.shape.v[0], sj.normal) > 0) f = point_to_polygon(q.position, ri.normal, sj.shape);
      weights.push_back(q.weight * f);
      const Vec3 from = q.position + ri.normal * offset;
      for (int k = 0; k < per_point; ++k) {
        const Vec3 y = sample_polygon(sj.shape, rng.uniform(), rng.uniform());
        segments.push_back({from, y + sj.normal * offset});
        kernel.push_back(point_kernel(q.position, ri.normal, y, sj.normal));
      }
    }
    visibility(p, segments, visible);
    // Control variate (unbiased): the exact unoccluded point form factor minus a Monte Carlo
    // estimate of its occluded part, (A_j/π) E[cos cos / r² · blocked]. Visibility as a fraction
    // of rays (even weighted) is biased where occluders sit near either end, and those biases
    // add up to lost power in cluttered rooms.
    // A link whose every ray is blocked sees nothing of the source: 0, not the control variate's
    // unbiased but noisy difference, which is positive half of the time and leaked light into
    // closed rooms (stability suite, junctions). Per point it would bias: one ray a point is common.
    // Through volumes no ray is ever wholly blocked (transmittance exp(−τ) > 0): where most of
    // the source is hidden the control variate is all noise, so the plain estimate of the part
    // that arrives, (A_j/π) E[cos cos / r² · visible], is used instead (unbiased as well).
    double sum = 0, direct = 0, open = 0, shut = 0;
    size_t hidden = 0;
    for (size_t q = 0; q < pts.size(); ++q) {
      double occluded = 0, arrives = 0;
      for (int k = 0; k < per_point; ++k) {
        const double v = visible[q * per_point + k];
        occluded += kernel[q * per_point + k] * (1.0 - v);
        arrives += kernel[q * per_point + k] * v;
        hidden += v == 0.0;
      }
      const double f = weights[q] - pts[q].weight * sj.area / kPi * (per_point ? occluded / per_point : 0.0);
      sum += f;
      if (per_point) direct += pts[q].weight * sj.area / kPi * arrives / per_point;
      open += arrives;
      shut += occluded;
    }
    if (!segments.empty() && hidden == segments.size()) sum = 0;
    if (p.volume && open < shut) sum = direct;
    sum = std::max(0.0, sum);
    p.F = sum / ri.area;
    // Variation of the point form factor over the receiver, from its quadrature points.
    double lo = INFINITY, hi = 0;
    for (size_t q = 0; q < pts.size(); ++q) {
      const double f = pts[q].weight > 0 ? weights[q] / pts[q].weight : 0.0;
      lo = std::min(lo, f);
      hi = std::max(hi, f);
    }
    p.spread = pts.empty() ? 0.0 : hi - lo;
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
  double mc = 0, weighted = 0, open = 0;
  int drawn = 0, facing = 0;
  std::vector<ClusterSample>& drawn_samples = cluster_scratch_;
  drawn_samples.clear();
  for (; drawn < n || (facing < (n + 3) / 4 && drawn < 8 * n); ++drawn) {
    Vec3 pi, ni, pj, nj;
    uint32_t child = 0;
    h_.sample(ri, rng.uniform(), rng.uniform(), rng.uniform(), pi, ni, &child);
    h_.sample(sj, rng.uniform(), rng.uniform(), rng.uniform(), pj, nj);
    drawn_samples.push_back({child, 0.0, -1});
    const Vec3 d = pj - pi;
    const double r2 = dot(d, d);
    if (r2 <= 0) continue;
    const Vec3 u = d / std::sqrt(r2);
    const double ci = dot(ni, u), cj = -dot(nj, u);
    if (ci <= 0 || cj <= 0) continue;
    const double kernel = ci * cj * sj.area / (kPi * r2);  // finite: linked clusters do not overlap
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
  if (ri.cluster) p.spread = misplaced(ri, drawn_samples, visible);
  for (size_t k = 0; k < segments.size(); ++k) {
    weighted += weights[k];
    open += weights[k] * visible[k];
  }
  // F = unoccluded − occluded part. The unoccluded form factor is exact for few polygon pairs and
  // the Monte Carlo mean otherwise; the occluded part, (1/N) Σ K · blocked, is an unbiased estimate
  // from the same samples (a control variate: no ratio, so no bias from few facing samples).
  const double occluded = (weighted - open) / drawn;
  const double unoccluded = polygon_pairs(ri, sj) <= kExactClusterPairs ? exact_unoccluded(ri, sj) : mc / drawn;
  // Not capped above (a cap at min(1, A_j/A_i) would bias the estimate low); rows that sum to too
  // much are caught at the leaves (push_pull). Every ray blocked: 0 (as for elements above).
  const bool all_blocked = !segments.empty() && open == 0;
  // Mostly hidden through volumes: the plain estimate, as for elements above.
  const bool mostly_hidden = p.volume && open < weighted - open;
  p.F = all_blocked ? 0.0 : std::max(0.0, mostly_hidden ? open / drawn : unoccluded - occluded);
}

double Solver::misplaced(const HNode& receiver, const std::vector<Solver::ClusterSample>& samples, const std::vector<double>& visible) {
  constexpr uint32_t kMaxChildren = 8;
  if (receiver.child_count < 2 || receiver.child_count > kMaxChildren || samples.empty()) return 0.0;
  double sum[kMaxChildren] = {}, sq[kMaxChildren] = {}, count[kMaxChildren] = {};
  double total = 0;
  for (const ClusterSample& s : samples) {
    const double v = s.segment >= 0 ? s.value * visible[size_t(s.segment)] : s.value;
    sum[s.child] += v;
    sq[s.child] += v * v;
    count[s.child] += 1;
    total += v;
  }
  const double mean = total / double(samples.size());
  double out = 0;
  for (uint32_t c = 0; c < receiver.child_count; ++c) {
    if (count[c] < 1) continue;
    const double m = sum[c] / count[c];
    const double var = std::max(0.0, sq[c] / count[c] - m * m);
    const double error = 2.0 * std::sqrt(var / count[c]);
    out += count[c] / double(samples.size()) * std::max(0.0, std::fabs(m - mean) - error);
  }
  return out;
}

double Solver::point_kernel(const Vec3& x, const Vec3& nx, const Vec3& y, const Vec3& ny) {
  const Vec3 d = y - x;
  const double r2 = dot(d, d);
  if (r2 <= 0) return 0;
  return std::max(0.0, dot(nx, d)) * std::max(0.0, -dot(ny, d)) / (r2 * r2);
}

uint64_t Solver::polygon_pairs(const HNode& a, const HNode& b) const {
  return uint64_t(a.cluster ? h_.polygon_count(a) : 1) * uint64_t(b.cluster ? h_.polygon_count(b) : 1);
}

double Solver::exact_unoccluded(const HNode& ri, const HNode& sj) const {
  auto shapes = [&](const HNode& n) {
    std::vector<Polygon> out;
    if (!n.cluster) {
      out.push_back(n.shape);
    } else {
      for (uint32_t k = h_.polygon_begin(n); k < h_.polygon_begin(n) + h_.polygon_count(n); ++k)
        out.push_back(h_.scene().polygons[h_.tree().polygons[k]]);
    }
    return out;
  };
  const std::vector<Polygon> rs = shapes(ri), ss = shapes(sj);
  double sum = 0;
  for (const Polygon& a : rs) {
    const double area = polygon_area(a);
    for (const Polygon& b : ss)
      if (&a != &b && !(a.v == b.v && a.count == b.count)) sum += area * element_to_element(a, b);
  }
  return ri.area > 0 ? sum / ri.area : 0.0;
}

}  // namespace walkrad::hierarchical_detail
