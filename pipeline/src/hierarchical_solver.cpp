#include "walkrad/pipeline/hierarchical_solver.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "walkrad/pipeline/formfactor.h"
#include "walkrad/pipeline/link_transport.h"
#include "walkrad/pipeline/punctual_lights.h"
#include "walkrad/pipeline/transmission.h"
#include "walkrad/pipeline/sampling.h"
#include "walkrad/pipeline/shaft.h"
#include "walkrad/pipeline/rounding.h"

namespace walkrad {

namespace {

// Mean max(cos, 0) over random orientations: a cluster's mean projected area is A/4 (Sillion 1995).
// Used by the refinement oracle's estimate; link form factors use each surface's own cosine.
constexpr double kClusterCosine = 0.25;

struct Pending {
  uint32_t receiver, source;
  bool need_rays;   // Embree rays (against the solid scene when volume)
  int samples = 0;  // rays (or Monte Carlo samples) for this link
  bool volume = false;  // volume clusters in the shaft stand in for their polygons (volume_visibility.h)
  double F = 0, spread = 0;
  uint64_t rays = 0, grid_segments = 0;
};

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

class Solver {
 public:
  Solver(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& s, HierarchicalStats& stats)
      : h_(h), rays_(rays), s_(s), stats_(stats) {
    const HNode& root = h_[h_.root()];
    mark_two_sided_clusters();
    // Punctual lights first: what they deliver to the surfaces counts in the power Φ that scales ε.
    if (lights()) {  // every element is an input polygon's root here
      for (uint32_t i = 0; i < h_.nodes().size(); ++i)
        if (!h_[i].cluster) light_frontier_.push_back(i);
      light_spread_ = direct_for(light_frontier_);
    }
    Vec3 emitted;
    for (const HNode& n : h_.nodes())
      if (!n.cluster) emitted += (n.emission + n.D) * n.area;
    const double power = luminance(emitted);
    eps_ = s_.epsilon * power;
    stats_.epsilon_absolute = eps_;
    min_area_ = s_.min_area > 0 ? s_.min_area : std::pow(2.0 * root.radius / 256.0, 2);
    // Changes are measured relative to the leaf's radiosity, but not below 1e-9 of the brightest
    // emitter's: a closed dark room's last traces of light decay by ρ per sweep and would keep their
    // relative change until they underflow (3,853 sweeps in the junction scene).
    for (const HNode& n : h_.nodes())
      if (!n.cluster) change_floor_ = std::max(change_floor_, 1e-9 * max_component(n.emission + mul(n.rho, n.D)));
    // Importance: scaled so that Σ R = Σ A, then B·I·ρ·F and the BF oracle B·A·ρ·F share ε.
    importance_ = s_.use_importance && root.R > 0;
    stats_.oracle = importance_ ? "importance" : "BF";
    if (importance_) {
      const double scale = root.area / root.R;
      for (HNode& n : h_.nodes()) {
        n.R *= scale;
        n.I = n.R;
      }
    }
  }

  // Elements split where the punctual lights' irradiance varies more than ε allows, level by level
  // (the irradiance of each level's new elements computed in parallel; the splits in a fixed order).
  void refine_for_lights() {
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

  // Clusters that hold a transmitting polygon or its twin (transmission.h). A cluster link sends the
  // area mean of its surfaces' radiosity and pushes what it receives evenly onto them, but the two
  // sides of a lampshade see different worlds: the bright inside, hidden from the room, and the room.
  // With the twins in a cluster, the lit outside of a shade gathered a row sum of 0.24, and a closed
  // room lost light (the transmission test's room absorbed 0.9958 of the emitted power; 1.000000 now;
  // the lamp room, whose leak lies elsewhere, absorbs 0.9965 without this and 0.9957 with it: see
  // docs/numerics.md). Links never end at such a cluster: they go down to the transmitting polygons'
  // own elements (a lampshade's few polygons; many transmitting polygons make many links).
  void mark_two_sided_clusters() {
    if (!s_.twins) return;
    two_sided_.assign(h_.nodes().size(), 0);
    for (uint32_t k = 0; k < h_.nodes().size(); ++k) {
      if (h_[k].cluster || h_[k].depth != 0 || (*s_.twins)[h_[k].polygon] == kNoTwin) continue;
      for (int32_t a = h_[k].parent; a >= 0 && !two_sided_[uint32_t(a)]; a = h_[uint32_t(a)].parent) two_sided_[uint32_t(a)] = 1;
    }
  }
  bool two_sided(uint32_t i) const { return i < two_sided_.size() && two_sided_[i]; }

  // Rounds of refine → evaluate → solve. A round that adds no link solves to convergence; the
  // search stops only when a refinement pass over the converged solution adds none either (links
  // kept while B was still growing are checked again against the final B).
  void run(const std::function<void(const IterationStats&)>& progress) {
    bool converged_before = false;
    for (int it = 0; it < s_.max_iterations; ++it) {
      IterationStats is;
      const size_t before = pending_.size();
      if (it == 0) {
        refine_for_lights();
        refine(h_.root(), h_.root(), nullptr);
      } else {
        refine_existing();
      }
      if (lights()) compute_missing_direct();  // elements the refinement created
      is.new_links = pending_.size() - before;
      evaluate_pending(is);
      if (s_.closed && is.new_links > 0) balance_closed();  // factors and B must match at the end
      const bool settled = is.new_links == 0;
      if (settled && converged_before) {
        is.change = 0;
        record(is, progress);
        stats_.converged = true;
        break;
      }
      const int sweeps = settled ? 1000 : s_.sweeps;
      for (int sweep = 0; sweep < sweeps; ++sweep) {
        ++is.sweeps;
        is.change = solve_sweep(is);
        if (s_.accelerate && s_.indirect && !s_.twins) {
          is.change = std::max(is.change, aggregation_correction(h_, change_floor_));
          ++stats_.corrections;
        }
        if (is.change <= s_.tolerance) break;
      }
      converged_before = is.change <= s_.tolerance;
      record(is, progress);
    }
    measure_left_error();
  }

  // A closed scene: every leaf receives a row sum of 1 and sends all of its power (link_transport.h).
  void balance_closed() {
    const BalanceStats b = balance_closed_transport(h_);
    stats_.balance_iterations += b.iterations;
    stats_.balance_row_error = b.row_error;
    stats_.balance_column_error = b.column_error;
    stats_.balance_unbalanced = b.unbalanced;
  }

  void record(IterationStats& is, const std::function<void(const IterationStats&)>& progress) {
    is.links = stats_.links;
    is.elements = h_.element_count();
    if (is.emitted == Vec3{} && !stats_.iterations.empty()) {  // no solve this round: keep the last
      is.emitted = stats_.iterations.back().emitted;
      is.absorbed = stats_.iterations.back().absorbed;
      is.residual = stats_.iterations.back().residual;
    }
    stats_.iterations.push_back(is);
    if (progress) progress(is);
  }

 private:
  double weight(const HNode& n) const { return importance_ ? n.I : n.area; }

  // τ of an element's material when transmission is simulated (else 0).
  Vec3 transmittance(const HNode& n) const {
    if (!s_.twins || n.cluster || (*s_.twins)[n.polygon] == kNoTwin) return {};
    return h_.scene().materials[h_.scene().polygons[n.polygon].material].transmittance;
  }
  Vec3 twin_irradiance(const HNode& n) const { return twin_received(h_, n, (*s_.twins)[n.polygon]); }
  const std::vector<PunctualLight>* lights() const { return s_.lights && !s_.lights->empty() ? s_.lights : nullptr; }

  // Direct irradiance of the given elements (4 × 4 points each, a shadow ray per point and light), in
  // parallel; returns each one's spread.
  std::vector<double> direct_for(const std::vector<uint32_t>& elements) {
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

  void compute_missing_direct() {
    std::vector<uint32_t> missing;
    for (uint32_t i = 0; i < h_.nodes().size(); ++i)
      if (!h_[i].cluster && !h_[i].D_known) missing.push_back(i);
    direct_for(missing);
  }

  bool splittable(uint32_t i) const {
    const HNode& n = h_[i];
    if (n.cluster) return n.child_count > 0;
    return n.depth < s_.max_depth && n.area * 0.25 >= min_area_;
  }

  // Unoccluded form factor estimate from centres (Hanrahan et al.: a disc of the source's area),
  // taking cosines as 1 when the two are close to each other's size (no trust in centre angles).
  double estimate(const HNode& ri, const HNode& sj) const {
    const Vec3 d = sj.center - ri.center;
    const double r2 = dot(d, d), r = std::sqrt(r2);
    const bool near = clearly_greater(2.0 * (ri.radius + sj.radius), r);
    const Vec3 u = r > 0 ? d / r : Vec3{};
    const double ci = ri.cluster ? kClusterCosine : (near ? 1.0 : std::max(0.0, dot(ri.normal, u)));
    const double cj = sj.cluster ? kClusterCosine : (near ? 1.0 : std::max(0.0, -dot(sj.normal, u)));
    return ci * cj * sj.area / (kPi * r2 + sj.area);
  }

  double oracle(const HNode& ri, const HNode& sj) const {
    return luminance(sj.B) * weight(ri) * luminance(ri.rho) * estimate(ri, sj);
  }

  // Refines the interaction of receiver i with source j: links it, drops it, or splits an end and
  // recurses. parent: the candidate occluders of the enclosing link's shaft (null: from the tree).
  void refine(uint32_t i, uint32_t j, const std::vector<uint32_t>* parent) {
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
    pending_.push_back({i, j, s_.visibility && blockers > size_t(volumes > 0), samples, s_.visibility && volumes > 0});
  }

  // The polygons that can block between nodes i and j (shaft.h); with volumetric visibility, volume
  // clusters the multi-resolution rule accepts for this link stand whole (tagged). A shaft where the
  // rule accepts some volumes but another volume's polygons must block exactly is evaluated exactly
  // throughout: the grid holds every volume, the solid scene none.
  std::vector<uint32_t> occluders(uint32_t i, uint32_t j, const Shaft& shaft, uint32_t ex_i, uint32_t ex_j,
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

  // Later rounds: links whose oracle now exceeds ε (B and I have changed) are split.
  void refine_existing() {
    const size_t n = h_.nodes().size();
    for (size_t i = 0; i < n; ++i) {
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

  // Form factors of the new links, in parallel: each link draws from its own random stream.
  void evaluate_pending(IterationStats& is) {
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

  // What of each segment arrives: 0 or 1 from Embree (against the solid scene when the link sees
  // through volumes), times the transmittance through the extinction grid.
  void visibility(Pending& p, const std::vector<RayScene::Segment>& segments, std::vector<double>& visible) const {
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

  void evaluate(Pending& p, std::vector<RayScene::Segment>& segments, std::vector<double>& visible,
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

  static constexpr uint64_t kExactClusterPairs = 64;

  // A Monte Carlo sample of a link with a cluster receiver: which child of the receiver its point
  // lies in, its kernel (0 when the two points do not face each other), its ray (−1: none).
  struct ClusterSample {
    uint32_t child;
    double value;
    int32_t segment;
  };

  // What pushing a cluster link's transfer uniformly to the receiver's children misplaces: the mean
  // over children (by their share of samples, i.e. of area) of how far each child's own estimate lies
  // from the link's, beyond twice its statistical error (so that a uniformly lit cluster is not split
  // for noise). A child facing away or hidden behind others (a closed room's inner walls) gets nothing
  // of what the others get: the link's receiver is split where that matters (refine_existing).
  static double misplaced(const HNode& receiver, const std::vector<ClusterSample>& samples, const std::vector<double>& visible) {
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

  // The form factor kernel between two surface points, cos θ cos θ' / r² (without the constant).
  static double point_kernel(const Vec3& x, const Vec3& nx, const Vec3& y, const Vec3& ny) {
    const Vec3 d = y - x;
    const double r2 = dot(d, d);
    if (r2 <= 0) return 0;
    return std::max(0.0, dot(nx, d)) * std::max(0.0, -dot(ny, d)) / (r2 * r2);
  }

  uint64_t polygon_pairs(const HNode& a, const HNode& b) const {
    return uint64_t(a.cluster ? h_.polygon_count(a) : 1) * uint64_t(b.cluster ? h_.polygon_count(b) : 1);
  }

  // (1/A_i) Σ_{k ∈ i} Σ_{m ∈ j} A_k F_km over the polygons (or the element) of each end.
  double exact_unoccluded(const HNode& ri, const HNode& sj) const {
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

  // One Jacobi sweep: gather along all links, push-pull radiosity, shoot and push-pull importance.
  // Returns the largest relative change of a leaf's radiosity.
  // One sweep: gather along the links, push-pull radiosity, shoot and push-pull importance. Jacobi
  // gathers every node from the previous sweep's radiosity; Gauss-Seidel gathers each input polygon's
  // quadtree just before pushing it down, so it sees what the polygons before it got this sweep
  // (clusters still gather first). Returns the largest relative change of a leaf's radiosity.
  double solve_sweep(IterationStats& is) {
    std::vector<HNode>& nodes = h_.nodes();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i)
        if (!s_.gauss_seidel || nodes[i].cluster) gather(nodes[i]);
    });
    change_ = 0;
    is.emitted = is.absorbed = is.residual = Vec3{};
    is.clamped_leaves = 0;
    push_pull(h_.root(), Vec3{}, 0.0, is);
    if (importance_) {
      for (HNode& n : nodes) n.Ig = 0;
      for (const HNode& n : nodes)  // sequential: sums in a fixed order
        for (const Link& l : n.links) nodes[l.source].Ig += luminance(n.rho) * l.F * n.I;
      push_pull_importance(h_.root(), 0.0);
    }
    return change_;
  }

  // Pushes irradiance H and the row sum S (Σ F along the path) down. A leaf whose row sum is well
  // above 1 receives more than any enclosure could send it: coincident surfaces in the input (two
  // lamp shades in one place: S = 3.5 in the MGF hospital) create power there and make the iteration
  // diverge. Its irradiance is scaled back to a row sum of 1. Row sums slightly above 1 are left: near
  // corners pushed averages overstate some leaves and understate others (up to 1.24 in the furnace),
  // and clamping only one side would lose power.
  void gather(HNode& n) {
    Vec3 H;
    double f = 0;
    for (const Link& l : n.links) {
      H += (s_.indirect ? h_[l.source].Bt : h_[l.source].emission) * l.F;
      f += l.F;
    }
    n.H = H;
    n.Fsum = f;
  }

  void gather_subtree(uint32_t i) {
    gather(h_[i]);
    for (uint32_t k = 0; k < h_[i].child_count; ++k) gather_subtree(h_.child(h_[i], k));
  }

  Vec3 push_pull(uint32_t i, const Vec3& down, double down_sum, IterationStats& is) {
    if (s_.gauss_seidel && !h_[i].cluster && h_[i].depth == 0) gather_subtree(i);
    HNode& n = h_[i];
    Vec3 H = n.H + down;
    const double row_sum = n.Fsum + down_sum;
    if (n.child_count == 0) {
      bool clamped = false;
      H = leaf_irradiance(n, H, row_sum, &clamped);
      if (clamped) ++is.clamped_leaves;
      h_[i].Hl = H;
      const Vec3 tau = transmittance(n);
      const Vec3 through = tau == Vec3{} ? Vec3{} : mul(tau, twin_irradiance(n));
      const Vec3 b = n.emission + mul(n.rho, H + n.D) + through;
      const double scale = std::max(max_component(b), change_floor_);
      if (scale > 0) change_ = std::max(change_, max_component(Vec3(std::fabs(b.x - n.B.x), std::fabs(b.y - n.B.y), std::fabs(b.z - n.B.z))) / scale);
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
    for (uint32_t k = 0; k < count; ++k) {
      const uint32_t c = h_.child(h_[i], k);
      sum += push_pull(c, H, row_sum, is) * h_[c].area;
      sent += h_[c].Bt * h_[c].area;
    }
    h_[i].B = area > 0 ? sum / area : Vec3{};
    h_[i].Bt = area > 0 ? sent / area : Vec3{};
    return h_[i].B;
  }

  double push_pull_importance(uint32_t i, double down) {
    const double total = h_[i].Ig + down;
    if (h_[i].child_count == 0) return h_[i].I = h_[i].R + total;
    double sum = 0;
    const double area = h_[i].area;
    for (uint32_t k = 0; k < h_[i].child_count; ++k) {
      const uint32_t c = h_.child(h_[i], k);
      sum += push_pull_importance(c, area > 0 ? total * h_[c].area / area : 0.0);
    }
    return h_[i].I = sum;
  }

  // What the final links still carry above nothing: B·W·ρ·F, the error the user sees as coarse.
  void measure_left_error() {
    for (const HNode& n : h_.nodes())
      for (const Link& l : n.links) {
        const double e = luminance(h_[l.source].B) * weight(n) * luminance(n.rho) * l.F;
        stats_.left_error_max = std::max(stats_.left_error_max, e);
        stats_.left_error_sum += e;
      }
  }

  Hierarchy& h_;
  const RayScene& rays_;
  const HierarchicalSettings& s_;
  HierarchicalStats& stats_;
  double eps_ = 0, min_area_ = 0, change_ = 0, change_floor_ = 0;
  std::vector<uint32_t> light_frontier_;  // the input polygons' elements and their punctual-light spread,
  std::vector<double> light_spread_;      // from the constructor to refine_for_lights
  bool importance_ = false;
  std::vector<Pending> pending_;
  static thread_local std::vector<double> kernel_scratch_;
  static thread_local std::vector<ClusterSample> cluster_scratch_;
  std::vector<uint8_t> two_sided_;  // by node: a cluster holding a transmitting polygon or a twin
  static thread_local std::vector<uint8_t> blocked_scratch_;
};

thread_local std::vector<double> Solver::kernel_scratch_;
thread_local std::vector<Solver::ClusterSample> Solver::cluster_scratch_;
thread_local std::vector<uint8_t> Solver::blocked_scratch_;

}  // namespace

void solve_hierarchical(Hierarchy& h, const RayScene& rays, const HierarchicalSettings& settings, HierarchicalStats& stats,
                        const std::function<void(const IterationStats&)>& progress) {
  stats = {};
  if (h.nodes().empty()) return;
  Solver solver(h, rays, settings, stats);
  solver.run(progress);
}

}  // namespace walkrad
