#include "walkrad/hierarchical/point_radiosity.h"

#include <algorithm>
#include <cmath>
#include <atomic>
#include <cstring>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/formfactor/form_factor.h"
#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/hierarchical/cluster_radiosity.h"
#include "walkrad/hierarchical/directional_irradiance.h"
#include "walkrad/hierarchical/link_owners.h"
#include "walkrad/hierarchical/link_transport.h"
#include "walkrad/hierarchical/transmission.h"

namespace walkrad {

namespace {

// Centre distances below this many times the two radii count as near.
constexpr double kNear = 3.0;
// At a gathered vertex, a source farther than this many times its radius is taken as a disc of its area
// (A cos θ cos θ' / (π r² + A)): on office-floor's 8 rooms the contour formula at every vertex for every
// element source took 30 s of the bake's 77 (16 s with 8). On the Cornell box 4, 8 and ∞ gave 1.01,
// 0.95 and 0.92% weighted RMS.
constexpr double kFar = 4.0;
// A near source's part closer to the point than this many of its radii is taken by its own parts.
constexpr double kPart = 2.0;

// A link's visible fraction above this saw its source whole (F and F_open agree to float rounding).
constexpr double kWhole = 0.999;

// Whether a point is close enough to a source for its parts (its children, or a leaf's resolved parts:
// ClusterGather::resolve_close_sources) to be taken one by one.
bool within_parts(const HNode& s, const Vec3& x) { return length(s.center - x) < kPart * s.radius; }
bool by_parts(const HNode& s, const Vec3& x) { return s.child_count == 4 && within_parts(s, x); }

// A leaf element source is resolved into parts for a seen leaf at most this fraction of its size (its
// points see parts of it: test ContactShadow's floor beside the box, 1.6 cm leaves, and the box's
// 7.5 cm faces). Beside the box 0.3, 0.5, 1 and any size give the same error; on the Cornell box 0.5
// resolves 329 sources, 1 resolves 1,622 (over twice the time).
constexpr double kFinerReceiver = 0.5;

}  // namespace

bool taken_at_points(const Hierarchy& h, const HNode& r, const Link& l) {
  const HNode& s = h[l.source];
  return !s.cluster && l.open > 0 && length(s.center - r.center) < kNear * (r.radius + s.radius);
}

ClusterGather::ClusterGather(const Hierarchy& h, bool indirect, const std::vector<PunctualLight>* lights, const RayScene* rays)
    : h_(h), indirect_(indirect), lights_(lights && !lights->empty() ? lights : nullptr), rays_(rays),
      H_(h.scene().polygons.size()), Hg_(h.scene().polygons.size()), row_(h.scene().polygons.size(), 0.0),
      emitted_(emitted_as_sent(h)) {
  if (indirect_) {  // clusters send by direction (cluster_radiosity.h), as the solve took them
    facing_ = facing_radiosity(h, [&](uint32_t k) { return h[k].Bt; });
    facing_g_ = facing_radiosity(h, [&](uint32_t k) { return h[k].Bt - emitted_[k]; });
  }
  // Down the cluster tree by direction: all that is sent, and what is reflected.
  gather_down_clusters<2>(
      h, [&](const Link& l, const HNode& n) { return std::array<Vec3, 2>{sent(l, false, n.center), sent(l, true, n.center)}; },
      [&](uint32_t root, const std::array<DirectionalIrradiance, 2>& cubes) {
        const HNode& e = h[root];
        H_[e.polygon] = cubes[0].at(e.normal);
        Hg_[e.polygon] = cubes[1].at(e.normal);
        row_[e.polygon] = cubes[0].row(e.normal);
      });
}

Vec3 ClusterGather::sent(uint32_t node, bool gathered) const {
  const HNode& s = h_[node];
  if (!indirect_) return gathered ? Vec3{} : s.emission;
  return gathered ? s.Bt - emitted_[node] : s.Bt;
}

Vec3 ClusterGather::sent(const Link& l, bool gathered, const Vec3& receiver) const {
  return link_radiosity_towards(h_, l, receiver, gathered ? facing_g_ : facing_,
                                [&](uint32_t node) { return sent(node, gathered); });
}

void ClusterGather::resolve_close_sources(const std::vector<uint32_t>& leaves, const std::vector<uint32_t>* twins) {
  const size_t count = h_.nodes().size();
  // The close leaf sources of the leaves' links (their own and their ancestors'): a union, the same
  // whichever leaf marks a source first, so the leaves are walked in parallel.
  std::unique_ptr<std::atomic<uint8_t>[]> close(new std::atomic<uint8_t>[count]());
  std::vector<uint32_t> distinct(leaves);
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  const LinkOwners& owners = h_.owners();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, distinct.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<uint32_t> stack;
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const uint32_t leaf = distinct[i];
      if (!owners.holds_polygon(h_[leaf].polygon)) continue;  // on its links' rank
      const HNode& n = h_[leaf];
      for (int32_t a = int32_t(leaf); a >= 0 && !h_[uint32_t(a)].cluster; a = h_[uint32_t(a)].parent)
        for (const Link& l : h_[uint32_t(a)].links) {
          const HNode& top = h_[l.source];
          if (top.cluster || l.open <= 0 || !(length(top.center - n.center) < kPart * top.radius + n.radius)) continue;
          // The source, or the leaves under it that near_parts reaches from the leaf's points.
          stack.assign(1, l.source);
          while (!stack.empty()) {
            const uint32_t k = stack.back();
            stack.pop_back();
            const HNode& s = h_[k];
            if (!(length(s.center - n.center) < kPart * s.radius + n.radius)) continue;
            if (s.child_count == 0 && n.radius < kFinerReceiver * s.radius) close[k].store(1, std::memory_order_relaxed);
            else if (s.child_count == 4)
              for (uint32_t c = 0; c < 4; ++c) stack.push_back(h_.child(s, c));
          }
        }
    }
  });
  std::vector<uint32_t> sources;
  for (uint32_t k = 0; k < count; ++k)
    if (close[k]) sources.push_back(k);
  if (owners.divided()) {  // links divided among ranks (link_owners.h): every rank's sources, merged
    std::vector<uint8_t> mine(sources.size() * sizeof(uint32_t));
    if (!mine.empty()) std::memcpy(mine.data(), sources.data(), mine.size());
    const std::vector<uint8_t> all = all_gather(mine);
    for (size_t at = 0; at + sizeof(uint32_t) <= all.size(); at += sizeof(uint32_t)) {
      uint32_t k;
      std::memcpy(&k, all.data() + at, sizeof(k));
      close[k] = 1;
    }
    sources.clear();
    for (uint32_t k = 0; k < count; ++k)
      if (close[k]) sources.push_back(k);
  }
  std::vector<SourceParts> parts(sources.size());
  constexpr int kParts = kPartSide * kPartSide;
  tbb::parallel_for(size_t(0), sources.size(), [&](size_t k) {
    const HNode& s = h_[sources[k]];
    // kPartSide = 4: the element's quadrants' quadrants, in split_element order.
    const std::array<Polygon, 4> quarters = split_element(s.shape);
    for (int q = 0; q < 4; ++q) {
      const std::array<Polygon, 4> sixteenths = split_element(quarters[size_t(q)]);
      for (int c = 0; c < 4; ++c) parts[k].shape[size_t(4 * q + c)] = sixteenths[size_t(c)];
    }
    // Each part's own point value, over the leaf's solved mean: not over the parts' mean. Beside a
    // contact the two differ: the leaf at the foot of a box's face takes its floor links' means, lit
    // floor and the box's shadow strip averaged, while the point values see the strip by the floor
    // leaves' own radiosity (near_parts). Rescaled to the leaf's mean, the parts kept the solve's
    // excess (test ContactShadow at --error 0.2, the floor 1 cm beside the box: 4.73% RMS; 2.91% so).
    if (!owners.holds_polygon(s.polygon)) return;  // its ratios from its links' rank, below
    // A transmitting source with its twin: read without it, lamp-room's shade showed only what it
    // reflects, a quarter of what it passes on, and the table under it came out 40% dark.
    const LeafRadiosity leaf(*this, sources[k], twins ? (*twins)[s.polygon] : kNoTwin);
    const double mean = std::max(0.0, luminance(s.B - s.emission));
    for (int p = 0; p < kParts; ++p) {
      const double b = std::max(0.0, luminance(leaf.at(polygon_centroid(parts[k].shape[size_t(p)]), false) - s.emission));
      parts[k].ratio[size_t(p)] = float(mean > 0 ? std::clamp(b / mean, 0.25, 4.0) : 1.0);
    }
  });
  if (owners.divided())
    share_owned<std::array<float, kParts>>(
        sources.size(), [&](size_t k) { return polygon_rank(h_, h_[sources[k]].polygon); },
        [&](size_t k) { return parts[k].ratio; }, [&](size_t k, const std::array<float, kParts>& r) { parts[k].ratio = r; });
  part_slot_.assign(count, -1);
  for (size_t k = 0; k < sources.size(); ++k) part_slot_[sources[k]] = int32_t(k);
  parts_ = std::move(parts);
}

void LeafRadiosity::source_at(uint32_t node, const Vec3& x, const Vec3& normal, const Vec3& sent, Vec3& H, double& f) const {
  const HNode& s = h_[node];
  // Only resolved leaves have parts: the lookup first, the distance only for them (this runs for every
  // near source of every gathered point).
  const ClusterGather::SourceParts* parts = clusters_.parts(node);
  if (parts && !within_parts(s, x)) parts = nullptr;
  if (!parts) {
    const double ff = point_to_polygon(x, normal, s.shape);
    H += sent * ff;
    f += ff;
    return;
  }
  for (size_t p = 0; p < parts->shape.size(); ++p) {
    const double ff = point_to_polygon(x, normal, parts->shape[p]);  // the parts' form factors sum to the source's
    H += sent * (ff * double(parts->ratio[p]));
    f += ff;
  }
}

LeafRadiosity::LeafRadiosity(const ClusterGather& clusters, uint32_t leaf, uint32_t twin, ChainReadings* chain)
    : clusters_(clusters), h_(clusters.hierarchy()), leaf_(leaf),
      flat_(h_[leaf].cluster || twin != kNoTwin) {
  if (flat_) {
    // A transmitting leaf keeps its mean, plus how the punctual lights' light varies over it on either
    // side: a bulb inside a shade lights the shade's inside unevenly, and τ passes that on outside.
    // The departures are from what B holds: the leaf's own D, and the twin's D where the solve took
    // it (twin_received: a coarser twin's mean). From the leaf's own mean on the back instead, the
    // shade's outside in lamp-room came out flattened, the bright middle below τ D alone (17% off).
    const HNode& n = h_[leaf];
    if (twin == kNoTwin || !clusters.lights()) return;
    tau_ = material_transmittance(h_, n);
    D_front_ = n.D;
    D_back_ = twin_direct(h_, n, twin);
    lit_sides_ = true;
    return;
  }
  const Hierarchy& h = h_;
  const HNode& n = h[leaf];
  quadrants_ = split_element(n.shape);
  H_.fill(clusters.H(n.polygon, false));
  Hg_.fill(clusters.H(n.polygon, true));
  row_.fill(clusters.row(n.polygon));
  rowg_ = row_;
  // What link l of r takes towards r, and where a ray to its source ends (visible_at: once a leaf, not
  // at each of its points).
  const RayScene* rays = clusters.rays();
  auto read = [&](const HNode& r, const Link& l) {
    const HNode& s = h[l.source];
    ChainReadings::Reading out{clusters.sent(l, false, r.center), clusters.sent(l, true, r.center), {}};
    const double visible = l.open > 0 ? l.F / double(l.open) : 0.0;
    if (!s.cluster && l.open > 0 && rays && visible > 0 && visible <= kWhole)
      out.target = polygon_centroid(s.shape) + s.normal * rays->offset();
    return out;
  };
  uint32_t below = leaf;  // the child of a on the way to the leaf: the element chain only
  for (int32_t a = int32_t(leaf); a >= 0 && !h[uint32_t(a)].cluster; below = uint32_t(a), a = h[uint32_t(a)].parent) {
    const HNode& r = h[uint32_t(a)];
    const bool own = uint32_t(a) == leaf;
    const uint32_t slot = own ? 0 : child_slot(h, below);
    // An ancestor's readings, kept from the leaf before where it was the same element.
    const std::vector<ChainReadings::Reading>* kept = nullptr;
    if (chain && !own && !r.links.empty()) {
      if (chain->levels.size() <= size_t(r.depth)) chain->levels.resize(size_t(r.depth) + 1);
      ChainReadings::Level& level = chain->levels[size_t(r.depth)];
      if (level.node != uint32_t(a)) {
        level.node = uint32_t(a);
        level.links.clear();
        for (const Link& l : r.links) level.links.push_back(carries(l) ? read(r, l) : ChainReadings::Reading{});
      }
      kept = &level.links;
    }
    for (size_t k = 0; k < r.links.size(); ++k) {
      const Link& l = r.links[k];
      if (!carries(l)) continue;  // nothing at the leaf, nor at any of its points
      const HNode& s = h[l.source];
      const ChainReadings::Reading reading = kept ? (*kept)[k] : read(r, l);
      const Vec3& sent = reading.sent;
      const Vec3& reflected = reading.reflected;
      // A source element near the receiver: the point's own form factor (the kernel changes within a
      // share's quadrant there; farther, the shares say enough). At a gathered vertex every element
      // source is taken at the point: the gather is what the walkthrough sees, and a quadrant's share
      // placed at a vertex is a staircase that Gouraud shading smooths into the wrong ramp.
      const bool point_form = !s.cluster && l.open > 0;
      const bool close = taken_at_points(h, r, l);
      if (point_form) near_.push_back({l.source, l.F / double(l.open), close, sent, reflected, reading.target});
      // As the solve pushes it: by the part's share (the leaf's own links by the quadrant the point
      // falls in).
      for (uint32_t q = 0; q < 4; ++q) {
        const double f = l.F * double(l.share[own ? q : slot]);
        if (!close) {
          H_[q] += sent * f;
          row_[q] += f;
        }
        if (!point_form) {
          Hg_[q] += reflected * f;
          rowg_[q] += f;
        }
      }
    }
  }
}

void LeafRadiosity::near_parts(uint32_t node, const Vec3& x, const Vec3& normal, bool gathered, Vec3& H, double& f) const {
  const HNode& s = h_[node];
  if (by_parts(s, x)) {
    for (uint32_t c = 0; c < 4; ++c) near_parts(h_.child(s, c), x, normal, gathered, H, f);
    return;
  }
  source_at(node, x, normal, clusters_.sent(node, gathered), H, f);  // the parts' form factors sum to the source's
}

// Whether a gathered point sees a source its link saw in part: one ray to the source's centre. The
// link's visible fraction is its leaf's mean; beside an occluder the point's own view differs (taken
// at the leaf's visibility, the walls the short block hides make the Cornell box's floor 1-3 cm in
// front of the block, in its shadow, 25-60% bright). One ray against four to the source's
// quadrants: the Cornell box 0.744% against 0.714% weighted RMS, for 1.08x and 1.31x its CPU.
double LeafRadiosity::visible_at(const Near& s, const Vec3& x) const {
  const RayScene* rays = clusters_.rays();
  if (!rays || s.visible <= 0 || s.visible > kWhole) return s.visible;
  const Vec3 from = x + h_[leaf_].normal * rays->offset();
  return rays->occluded(from, s.target) ? 0.0 : rays->has_glass() ? luminance(rays->transmittance(from, s.target)) : 1.0;
}

Vec3 LeafRadiosity::ray_origin(const Vec3& x) const {
  const RayScene* rays = clusters_.rays();
  if (!rays) return x;
  const HNode& n = h_[leaf_];
  Vec3 inward = n.center - x;
  inward = inward - n.normal * dot(inward, n.normal);
  const double len = length(inward);
  return x + (n.normal + (len > 0 ? inward / len : Vec3{})) * rays->offset();
}

Vec3 LeafRadiosity::at(const Vec3& x, bool gathered) const {
  const HNode& n = h_[leaf_];
  if (flat_) {
    if (!lit_sides_) return n.B;
    uint64_t rays = 0;
    const std::vector<PunctualLight>& lights = *clusters_.lights();
    const Vec3 origin = ray_origin(x), back_origin = origin - n.normal * (2 * dot(origin - x, n.normal));
    const Vec3 front = point_irradiance(x, n.normal, lights, clusters_.rays(), rays, &origin);
    const Vec3 back = point_irradiance(x, n.normal * -1.0, lights, clusters_.rays(), rays, &back_origin);
    const Vec3 b = n.B + mul(n.rho, front - D_front_) + mul(tau_, back - D_back_);
    return {std::max(0.0, b.x), std::max(0.0, b.y), std::max(0.0, b.z)};
  }
  const uint32_t q = quadrant_of(quadrants_, n.normal, x);
  Vec3 H = gathered ? Hg_[q] : H_[q];
  double row = gathered ? rowg_[q] : row_[q];
  Vec3 H_open;  // near sources the link saw whole: exact at the point
  double f_open = 0;
  for (const Near& s : near_) {
    if (!gathered && !s.close) continue;
    const HNode& src = h_[s.source];
    const Vec3 d = src.center - x;
    const double r2 = dot(d, d);
    if (!s.close && r2 > kFar * kFar * src.radius * src.radius) {
      // Far: a disc of the source's area, exact on its axis, many times cheaper than the contour.
      const double r = std::sqrt(r2);
      const double f = src.area * std::max(0.0, dot(d, n.normal) / r) * std::max(0.0, -dot(d, src.normal) / r) /
                       (kPi * r2 + src.area) * (gathered ? visible_at(s, x) : s.visible);
      (s.visible > kWhole ? H_open : H) += (gathered ? s.reflected : s.sent) * f;
      (s.visible > kWhole ? f_open : row) += f;
      continue;
    }
    if (dot(x - src.shape.v[0], src.normal) <= 0) continue;  // behind the source
    // Near: the source's parts that are near the point by their own form factors and radiosity
    // (the kernel varies over them: the Cornell box's block face towards the camera sees the floor
    // at its foot most: 4.9% → 3.3% off).
    Vec3 Hs;
    double fs = 0;
    if (by_parts(src, x)) near_parts(s.source, x, n.normal, gathered, Hs, fs);
    else source_at(s.source, x, n.normal, gathered ? s.reflected : s.sent, Hs, fs);
    const double v = gathered ? visible_at(s, x) : s.visible;
    (s.visible > kWhole ? H_open : H) += Hs * v;
    (s.visible > kWhole ? f_open : row) += fs * v;
  }
  if (gathered && n.balanced && row > 0 && f_open + row > 1 && scalable_row(f_open < 1 ? f_open + row : f_open)) {
    // A closed scene's row overfilled at the point: the links' visibility is their leaf's mean, and a
    // point where an occluder hides part of the sources (the table under lamp-room's shade, whose row
    // summed to 1.4) counts the occluder and what it hides. The excess is taken from the sources seen
    // in part, whose visibility the point does not know; those seen whole are exact here (the shade).
    // Where those alone fill the hemisphere, the others are hidden (beside a box, the walls behind it
    // that its leaf's ancestors half saw: 10% bright), and those are divided by their own row.
    return n.emission + mul(n.rho, H_open / std::max(1.0, f_open) + H * (std::max(0.0, 1 - f_open) / row));
  }
  H += H_open;
  row += f_open;
  // Gathered: the links' direct light is left for the gather's exact D, and a closed scene's row
  // scaling (the part of the hemisphere the links miss, filled at the mean of what they see) scales
  // the reflected light alone: the emitters' links are not what the links miss (office-floor's
  // direct-only bake: the gather agrees with the unscaled links to 0.1%). The vertex is scaled by its
  // own row, not by its leaf's receive factor: its near sources' form factors are exact at the point,
  // while the leaf's factor corrects the leaf's links, whose quadrature overfills rows beside close
  // geometry (a floor leaf 7 cm from a box: raw row 1.24, at the vertex 1.015) and would darken every
  // source to pay for the near ones.
  if (gathered && n.balanced && scalable_row(row)) return n.emission + mul(n.rho, H / row);
  if (gathered) return n.emission + mul(n.rho, leaf_irradiance(n, H, row));
  uint64_t rays = 0;
  const Vec3 origin = ray_origin(x);
  const Vec3 D = clusters_.lights() ? point_irradiance(x, n.normal, *clusters_.lights(), clusters_.rays(), rays, &origin) : n.D;
  return n.emission + mul(n.rho, leaf_irradiance(n, H, row) + D);
}

}  // namespace walkrad
