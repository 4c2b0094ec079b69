// The error a node's links leave in its radiosity, and the tolerance it is held to (see
// docs/numerics.md). Piecewise-constant hierarchical radiosity errs in three ways at a receiver:
// - its transfers fall unevenly on it, but are pushed to its children uniformly: the variation of the
//   total over its children (Link::share), not of each link alone, so that transfers which sum to a
//   uniform irradiance (a furnace, a wall beside a floor) are not refined however large they are
//   (the receiver-side error of Lischinski, Smits & Greenberg 1994; Holzschuch & Sillion 1998);
// - a source sends its mean radiosity where the receiver sees some of its parts more than others;
// - the form factor's own Monte Carlo noise (its standard error, Link::sigma).
// Each is compared with a tolerance relative to what the receiver shows, so that ε means the same in
// a white room and a grey one, in one room and in a hundred.
#include "error_oracle.h"

#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/formfactor/sky_light.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "link_evaluator.h"
#include "walkrad/core/rounding.h"
#include "walkrad/formfactor/form_factor.h"
#include "walkrad/hierarchical/cluster_radiosity.h"
#include "walkrad/hierarchical/hierarchy_walk.h"
#include "walkrad/hierarchical/link_owners.h"
#include "walkrad/hierarchical/link_transport.h"
#include "walkrad/hierarchical/transmission.h"

namespace walkrad::hierarchical_detail {

ErrorOracle::ErrorOracle(Hierarchy& h, const HierarchicalSettings& s, double quantum_area)
    : h_(h), s_(s), quantum_area_(quantum_area) {}

void ErrorOracle::weigh_by_importance(double seen_density) {
  importance_ = true;
  seen_density_ = seen_density;
}

void ErrorOracle::update_scales() {
  // Display weights: a node's leaves' largest (an error left at a cluster reaches every leaf below it,
  // seen or not). Children come after their parents. The first refinement takes the direct importance
  // only: the first round's cluster links spread the shot importance over whole buildings by area, and
  // what is refined on it stays refined.
  const size_t count = h_.nodes().size();
  state_.weight.assign(count, importance_ ? 0.0f : 1.0f);
  if (importance_) {
    nodes_bottom_up(h_, [&](uint32_t k) {  // in parallel: a maximum is the same in any order
      const HNode& n = h_[k];
      const double I = state_.direct_weights ? n.R : n.I;
      if (n.child_count == 0 && n.area > 0 && seen_density_ > 0) state_.weight[k] = float(std::min(1.0, I / (n.area * seen_density_)));
      for (uint32_t c = 0; c < n.child_count; ++c) state_.weight[k] = std::max(state_.weight[k], state_.weight[h_.child(n, c)]);
    });
  }
  // Emitters are left out, as the exposure leaves them out (a light may clip to white), unless the
  // scene holds nothing else (a furnace).
  std::vector<std::pair<double, double>> seen;  // luminance, weight
  double total = 0;
  for (const bool emitters : {false, true}) {
    for (const HNode& n : h_.nodes()) {
      if (n.cluster || n.child_count || (max_component(n.emission) > 0) != emitters) continue;
      const double w = n.area * display_weight(uint32_t(&n - h_.nodes().data()));
      if (w <= 0) continue;
      seen.push_back({luminance(n.B), w});
      total += w;
    }
    if (total > 0) break;
  }
  tbb::parallel_sort(seen.begin(), seen.end());  // pairs in a total order: the same whatever the threads
  double below = 0, p95 = 0;
  for (const auto& [b, w] : seen) {
    p95 = b;
    below += w;
    if (below >= 0.95 * total) break;
  }
  // Nothing lit yet (before the first sweeps): 0, and nothing is refined on it (worth_splitting).
  state_.white = p95 > 0 ? std::max(p95 / 0.9, kWhiteFloor * light_density()) : 0.0;
}

double ErrorOracle::light_density() const {
  if (light_density_ >= 0) return light_density_;
  double power = 0, area = 0;
  for (const HNode& n : h_.nodes())
    if (!n.cluster && n.depth == 0) {
      area += n.area;
      power += n.area * luminance(n.emission);
    }
  for (const PunctualLight& l : h_.scene().lights)  // at most
    power += l.type == PunctualLight::Type::directional ? luminance(directional_power(l, h_.scene().polygons))
             : l.type == PunctualLight::Type::sky       ? (l.sky ? luminance(l.intensity) * sky_power(*l.sky, h_.scene().polygons) : 0.0)
                                                        : 4 * kPi * luminance(l.intensity);
  light_density_ = area > 0 ? power / area : 0.0;
  return light_density_;
}

double ErrorOracle::display_weight(uint32_t i) const {
  if (!importance_) return 1.0;
  if (i < state_.weight.size()) return double(state_.weight[i]);
  // A node made this round: its own direct importance (its view hits follow it: Hierarchy::subdivide)
  // and its share by area of the indirect importance of the ancestor the last update weighed (push-pull
  // spreads it so), as update_scales weighs a leaf. Its parent's weight, the largest of its leaves',
  // let one seen metre of a corridor's 320 m floor refine all of it within one round.
  uint32_t a = i;
  while (a >= state_.weight.size() && h_[a].parent >= 0) a = uint32_t(h_[a].parent);
  if (a >= state_.weight.size() || seen_density_ <= 0 || h_[i].area <= 0 || h_[a].area <= 0) return 1.0;
  const HNode& n = h_[i];
  const HNode& ancestor = h_[a];
  const double indirect = state_.direct_weights ? 0.0 : std::max(0.0, ancestor.I - ancestor.R) * n.area / ancestor.area;
  return std::min(1.0, (n.R + indirect) / (n.area * seen_density_));
}

double ErrorOracle::tolerance(uint32_t i) const {
  const HNode& n = h_[i];
  const double shown = std::clamp(luminance(n.B), kDarkShare * state_.white, state_.white);
  const double w = display_weight(i);
  return w > 0 && shown > 0 ? s_.error * shown / w : INFINITY;  // nothing lit yet: nothing to refine
}

void ErrorOracle::measure_spread() {
  // Every subtree's range, each node after its children (in parallel: a minimum and a maximum are
  // the same in any order).
  const size_t n = h_.nodes().size();
  std::vector<float> lo(n, INFINITY), hi(n, -INFINITY);
  nodes_bottom_up(h_, [&](uint32_t k) {
    const HNode& node = h_[k];
    if (node.child_count == 0) lo[k] = hi[k] = float(luminance(sent(node)));
    for (uint32_t c = 0; c < node.child_count; ++c) {
      const uint32_t child = h_.child(node, c);
      lo[k] = std::min(lo[k], lo[child]);
      hi[k] = std::max(hi[k], hi[child]);
    }
  });
  state_.spread.assign(n, 0.0f);
  for (size_t i = 0; i < n; ++i)
    if (hi[i] >= lo[i]) state_.spread[i] = hi[i] - lo[i];
  state_.emitted.assign(n, 0.0f);
  if (!s_.gather) return;
  const std::vector<Vec3> emitted = emitted_as_sent(h_);
  for (size_t i = 0; i < n; ++i) state_.emitted[i] = float(luminance(emitted[i]));
}

bool ErrorOracle::gathered(uint32_t i) const {
  const HNode& n = h_[i];
  if (!s_.gather || n.cluster) return false;
  if (s_.gathered && !(*s_.gathered)[n.polygon]) return false;
  return !s_.twins || (*s_.twins)[n.polygon] == kNoTwin;
}

double ErrorOracle::reflected_sent(uint32_t source) const {
  if (!s_.indirect) return 0.0;  // sources send their emission alone
  // A node made this round: its parent's (an element's children share its emission).
  uint32_t j = source;
  while (j >= state_.emitted.size() && h_[j].parent >= 0) j = uint32_t(h_[j].parent);
  const double all = luminance(sent(h_[source]));
  return j < state_.emitted.size() ? std::max(0.0, all - double(state_.emitted[j])) : all;
}

Vec3 ErrorOracle::link_sent(const Link& l) const {
  Vec3 b;
  for_each_part(h_, l, [&](uint32_t node, double w) { b += sent(h_[node]) * w; });
  return b;
}

double ErrorOracle::reflected_sent(const Link& l) const {
  double b = 0;
  for_each_part(h_, l, [&](uint32_t node, double w) { b += reflected_sent(node) * w; });
  return b;
}

void ErrorOracle::measure_variation() {
  measure_spread();
  state_.variation.assign(h_.nodes().size(), 0.0f);
  state_.left.assign(h_.nodes().size(), 0.0f);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, h_.nodes().size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const HNode& n = h_[uint32_t(i)];
      const uint32_t kids = n.cluster ? n.child_count : 4;
      if (n.links.empty() || kids < 2 || kids > 4) continue;
      // The refinement measures everything the links carry; the estimate, at a gathered receiver, only
      // what its vertices take by the shares: the gather evaluates the emitters' light there, and the
      // element sources' light is taken at each vertex too (point_radiosity.cpp, LeafRadiosity), so
      // what those leave is the interpolation's departure between vertices, which the display
      // refinement measures and adds (display_refinement.cpp). Counted at the shares as well, the
      // estimate would be twice the measured error on the Cornell box and on corridor levels.
      const bool gather = gathered(uint32_t(i));
      double H = 0, Hc[4] = {}, G = 0, Gc[4] = {}, inner = 0;
      for (const Link& l : n.links) {
        const bool at_points = !h_[l.source].cluster && l.open > 0;
        const double b = luminance(link_sent(l)) * l.F, g = gather ? (at_points ? 0.0 : reflected_sent(l) * l.F) : b;
        H += b;
        G += g;
        inner += b * double(l.inner) / 64.0;  // 0 but from a luminaire (evaluate_elements)
        for (uint32_t k = 0; k < kids; ++k) {
          Hc[k] += b * double(l.share[k]);
          Gc[k] += g * double(l.share[k]);
        }
      }
      double worst = 0, squares = 0;
      for (uint32_t k = 0; k < kids; ++k) {
        const double rho = luminance(n.child_count ? h_[h_.child(n, k)].rho : n.rho);
        worst = std::max(worst, rho * std::fabs(Hc[k] - H));
        squares += rho * rho * (Gc[k] - G) * (Gc[k] - G);
      }
      // And inside the children, for the luminaires' links (emitters, and shades lit by punctual lights
      // inside: luminaire(), link_evaluator.h): a lamp 2 mm under a ceiling lights a wall most two thirds of the
      // way up and its top metre hardly at all, a peak inside each quadrant of the wall that the
      // shares flatten (test AWallUnderAGrazingLampKeepsItsProfileAtACoarseError).
      // Σ inner bounds it; where the bound passes the tolerance, the luminaires' irradiance is taken at
      // the centres of the children's quarters, so that transfers which cancel (a furnace's faces)
      // stay unsplit. Every link's inner variation, not only the emitters', would refine the Cornell box
      // no better than a finer tolerance does for as many links, and makes ContactShadow's floor worse.
      const double rho = luminance(n.rho);
      if (!n.cluster && rho * inner > worst && clearly_greater(rho * inner, tolerance(uint32_t(i))))
        worst = std::max(worst, rho * emitted_inner(uint32_t(i)));
      state_.variation[i] = float(worst);
      // Shares already give each child its own mean (the push and the vertices use them), so what is
      // left is the variation inside a child: for a transfer that varies linearly across the node, a
      // child's half-range equals its mean's distance from the node's, and a linear ramp's RMS about
      // its mean is its half-range / √3.
      state_.left[i] = float(std::sqrt(squares / double(kids) / 3.0));
    }
  });
  // A source's variation is read by the receivers that link to it, wherever they are held.
  share_element_values<std::array<float, 2>>(
      h_, [&](uint32_t i) { return std::array<float, 2>{state_.variation[i], state_.left[i]}; },
      [&](uint32_t i, const std::array<float, 2>& v) {
        state_.variation[i] = v[0];
        state_.left[i] = v[1];
      });
}

double ErrorOracle::emitted_inner(uint32_t i) const {
  // The luminaires' unoccluded irradiance at the centres of the quarters of each child (split_element
  // twice), times the fraction of each source its link sees; the largest departure of a quarter from
  // its child's mean.
  const HNode& n = h_[i];
  const std::array<Polygon, 4> kids = split_element(n.shape);
  double E[4][4] = {};
  Vec3 x[4][4];
  for (int c = 0; c < 4; ++c) {
    const std::array<Polygon, 4> quarters = split_element(kids[size_t(c)]);
    for (int q = 0; q < 4; ++q) x[c][q] = polygon_centroid(quarters[size_t(q)]);
  }
  for (const Link& l : n.links) {
    const HNode& s = h_[l.source];
    if (!luminaire(h_, s_, s) || l.open <= 0) continue;
    const double sent = luminance(link_sent(l)) * std::min(1.0, l.F / double(l.open));
    for (int c = 0; c < 4; ++c)
      for (int q = 0; q < 4; ++q)
        if (dot(x[c][q] - s.shape.v[0], s.normal) > 0) E[c][q] += sent * point_to_polygon(x[c][q], n.normal, s.shape);
  }
  double worst = 0;
  for (int c = 0; c < 4; ++c) {
    const double mean = 0.25 * (E[c][0] + E[c][1] + E[c][2] + E[c][3]);
    for (int q = 0; q < 4; ++q) worst = std::max(worst, std::fabs(E[c][q] - mean));
  }
  return worst;
}

double ErrorOracle::transfer_estimate(const HNode& ri, const HNode& sj) const {
  const Vec3 d = sj.center - ri.center;
  const double r2 = dot(d, d), r = std::sqrt(r2);
  const bool near = clearly_greater(2.0 * (ri.radius + sj.radius), r);
  const Vec3 u = r > 0 ? d / r : Vec3{};
  const double ci = ri.cluster ? kClusterCosine : (near ? 1.0 : std::max(0.0, dot(ri.normal, u)));
  const double cj = sj.cluster ? kClusterCosine : (near ? 1.0 : std::max(0.0, -dot(sj.normal, u)));
  return ci * cj * sj.area / (kPi * r2 + sj.area);
}

bool ErrorOracle::worth_splitting(uint32_t i, uint32_t j, bool occluded, const Link* link) const {
  if (state_.white <= 0) return false;  // nothing solved yet
  const HNode& ri = h_[i];
  const HNode& sj = h_[j];
  const double sent_b = luminance(sent(sj));
  const double spread = j < state_.spread.size() ? double(state_.spread[j]) : sj.parent >= 0 && size_t(sj.parent) < state_.spread.size()
                                                                        ? double(state_.spread[size_t(sj.parent)]) : 0.0;
  if (!occluded && !clearly_greater(spread, s_.error * sent_b)) return false;  // a uniform source in full view: exact
  // What the link may carry: the estimate from the centres, or its own form factor once evaluated; a
  // link whose every ray was blocked, what its n rays could have missed: the fraction below which n
  // blocked rays put what passes with 95% confidence, 3/n of its unoccluded form factor (3σ: the "rule
  // of three"). Not the centres' estimate: a corridor's 160 m ceiling is 80 m from a room's floor by
  // their centres, and a few centimetres from the doorway's threshold.
  const double F = !link ? transfer_estimate(ri, sj)
                   : link->F > 0 ? std::max(transfer_estimate(ri, sj), double(link->F))
                   : kHiddenBound * double(link->sigma);
  // What the link sends: its source's mean, or where the source's leaves range wider than that mean
  // and the receiver is near enough to see its parts unevenly (the source's radius against the
  // distance between them), the range: taking the mean errs by up to it there (a corridor's 160 m
  // wall, dark but for the patch its doorway lights, sends a mean 140 times below that patch to the
  // floor beside the door). A far or small source is seen alike in all its parts: its mean is right.
  const double near = std::min(1.0, sj.radius / std::max(length(sj.center - ri.center), 1e-300));
  const double carried = luminance(ri.rho) * std::max(sent_b, near * spread) * F * ri.area * display_weight(i);
  return clearly_greater(carried, s_.error * state_.white * quantum_area_);
}

double ErrorOracle::source_error(const HNode& ri, const Link& l, const std::function<bool(uint32_t)>& splittable) const {
  const HNode& sj = h_[l.source];
  const double rho = luminance(ri.rho);
  if (sj.child_count == 0) return splittable(l.source) ? 0.5 * rho * l.F * double(state_.variation[l.source]) : 0.0;
  // What the receiver would get from the source's parts two levels down (or one, where a child is a
  // leaf), each weighed by the kernel from the receiver's centre (cosines taken as 1 where the two are
  // too close for centre angles to mean anything, or at a cluster end), against the mean it sends.
  double weight = 0, weighted = 0;
  auto add = [&](const HNode& c) {
    const Vec3 d = c.center - ri.center;
    const double r = std::max(length(d), c.radius);
    const bool near = clearly_greater(2.0 * (ri.radius + c.radius), r);
    const double ci = ri.cluster || near ? 1.0 : std::max(0.0, dot(ri.normal, d) / r);
    const double cj = c.cluster || near ? 1.0 : std::max(0.0, -dot(c.normal, d) / r);
    const double w = c.area * ci * cj / (r * r);
    weight += w;
    weighted += w * luminance(sent(c));
  };
  for (uint32_t k = 0; k < sj.child_count; ++k) {
    const HNode& c = h_[h_.child(sj, k)];
    if (c.child_count == 0) add(c);
    for (uint32_t m = 0; m < c.child_count; ++m) add(h_[h_.child(c, m)]);
  }
  const double seen_parts = weight > 0 ? rho * l.F * std::fabs(weighted / weight - luminance(sent(sj))) : 0.0;
  // A link that sees only part of its source: what it sees need not send the mean, by up to half the
  // source's spread of radiosity (most where half of it is hidden).
  const double seen = l.open > 0 ? std::clamp(l.F / double(l.open), 0.0, 1.0) : 1.0;
  const double hidden = rho * l.F * double(state_.spread[l.source]) * std::min(seen, 1.0 - seen);
  return std::max(seen_parts, hidden);
}

uint64_t ErrorOracle::measure_left_error(const std::function<bool(uint32_t)>& here, const std::function<bool(uint32_t)>& splittable) {
  update_scales();
  measure_variation();
  // Each node's own (nodes in parallel: each writes its own error).
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(h_.nodes().size()), 1024), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t i = r.begin(); i != r.end(); ++i) {
      HNode& n = h_[i];
      if (!here(i)) continue;  // its holder's, below
      if (n.links.empty()) {
        n.error = 0;
        continue;
      }
      // An RMS, as the sweep measures: the variation's RMS left inside the children, not its worst
      // child (which the refinement tests), with the source's and the form factor's errors.
      double sq = double(state_.left[i]) * double(state_.left[i]);
      const double rho = luminance(n.rho);
      const bool gather = gathered(i);
      for (const Link& l : n.links) {
        const double carried = gather ? reflected_sent(l) : luminance(link_sent(l));
        const double source = source_error(n, l, splittable), noise = rho * carried * l.sigma;
        sq += source * source + noise * noise;
      }
      n.error = float(std::sqrt(sq));
    }
  });
  share_element_values<float>(h_, [&](uint32_t i) { return h_[i].error; },
                              [&](uint32_t i, float e) { h_[i].error = e; });
  uint64_t above = 0;
  for (uint32_t i = 0; i < h_.nodes().size(); ++i)
    if (h_[i].error / std::max(tolerance(i), 1e-300) > 1) ++above;
  return above;
}

}  // namespace walkrad::hierarchical_detail
