// The hierarchical solution evaluated at a point of a leaf element, for the output vertices: B(x) =
// E + ρ (D(x) + H(x)), D(x) the punctual lights' irradiance at the point (a shadow ray each), H(x) =
// Σ F(x → j) B_j over the links of the leaf and of its ancestors. A link from an element near the
// receiver takes the point's own form factor (the contour formula) times the fraction of the source
// the link sees (F / F_open); any other is taken as the solve pushes it (a cluster's by direction, an
// element's by the share of the child or quadrant the point lies in). The leaf's mean B is what the
// solve balances; a vertex is where the display interpolates, and an area mean placed at a vertex
// flattens every peak and fills every trough the leaf straddles (see docs/numerics.md).
// For a vertex of the final gather (final_gather.h) the direct light is evaluated at the point apart:
// there the sources send only what they reflect (Bt less their emission as sent) and punctual lights
// are left out, B(x) = E + ρ H_indirect(x), and the gather adds ρ D(x); and every element source, near
// or far, takes the point's own form factor times the fraction of it the link sees, or, where the link
// saw it in part, whether the point sees its centre (one ray: visibility at the point, not the leaf's).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/scene/transmission_twins.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

// Whether LeafRadiosity takes link l of element r (a link on a leaf's chain) at each point of the leaves
// below r by the point's own form factor, whether or not the point is gathered: a source element near r
// (centre distance below 3 times the two radii), where the kernel changes within a share's quadrant.
// Farther, the shares say enough (and a gathered point takes every element source at the point).
bool taken_at_points(const Hierarchy& h, const HNode& r, const Link& l);

// What the clusters' links push to each input polygon's element root (by its normal, as the solve
// does), gathered once for a whole hierarchy.
class ClusterGather {
 public:
  // indirect: sources send B (else only their emission, the effect plan's direct-only case).
  // lights, rays: punctual lights and their occluders, shot at each point (null: the leaf's mean).
  ClusterGather(const Hierarchy& h, bool indirect, const std::vector<PunctualLight>* lights = nullptr,
                const RayScene* rays = nullptr);
  const Hierarchy& hierarchy() const { return h_; }
  bool indirect() const { return indirect_; }
  const std::vector<PunctualLight>* lights() const { return lights_; }
  const RayScene* rays() const { return rays_; }
  // Irradiance and row sum at an element root (a polygon's), from every cluster above it; gathered:
  // indirect light only.
  const Vec3& H(uint32_t polygon, bool gathered) const { return gathered ? Hg_[polygon] : H_[polygon]; }
  // What a node sends along a link: everything (Bt, or its emission without indirect light), or for
  // a gathered vertex only what it reflects.
  Vec3 sent(uint32_t node, bool gathered) const;
  // What a link takes from its source (its parts by Link::seen) towards a receiver centred at
  // `receiver`: a cluster by direction (cluster_radiosity.h).
  Vec3 sent(const Link& l, bool gathered, const Vec3& receiver) const;
  double row(uint32_t polygon) const { return row_[polygon]; }

  // Near-contact sources: a leaf element sends one mean, but a point a fraction of its size away sees
  // mostly its nearest part (a floor point 1 cm from a box sees the first centimetres of the box's face,
  // which its bottom element, 7.5 cm tall, averages with brighter ones above). For every leaf element
  // that is a close source (its centre within 2 of its radii, plus the leaf's, of the leaf's centre) of
  // one of `leaves`' links or under such a source, and at least twice the leaf's size, its
  // kPartSide² parts and their radiosity, evaluated at their centres (LeafRadiosity::at, without these
  // parts), as a ratio to the leaf's solved mean: LeafRadiosity then takes such a source part by part.
  // In parallel over the sources; the result depends on no thread count.
  // twins (transmission_twins.h; null where transmission is off): a transmitting source's parts are
  // read as the mesher reads its vertices (with its twin), not as an opaque leaf's. No default, so that
  // no caller forgets them (lamp-room's table under the shade came out 40% dark).
  void resolve_close_sources(const std::vector<uint32_t>& leaves, const std::vector<uint32_t>* twins);
  static constexpr int kPartSide = 4;
  struct SourceParts {
    std::array<Polygon, kPartSide * kPartSide> shape;
    std::array<float, kPartSide * kPartSide> ratio;  // the part's point radiosity over the leaf's solved mean
  };
  const SourceParts* parts(uint32_t node) const {
    return node < part_slot_.size() && part_slot_[node] >= 0 ? &parts_[size_t(part_slot_[node])] : nullptr;
  }

 private:
  const Hierarchy& h_;
  bool indirect_;
  const std::vector<PunctualLight>* lights_;
  const RayScene* rays_;
  std::vector<Vec3> H_, Hg_;
  std::vector<double> row_;
  std::vector<Vec3> emitted_;  // per node: its emission as sent (emitted_as_sent)
  std::vector<std::array<Vec3, 6>> facing_, facing_g_;  // by cluster: Bt (and what it reflects) by facing
  std::vector<int32_t> part_slot_;  // per node: its SourceParts, or -1
  std::vector<SourceParts> parts_;
};

// What each link of an element takes from its source towards that element (ClusterGather::sent,
// gathered and not) and where rays to a source seen in part end: the same for every leaf below the
// element. Kept for the elements of one chain from the root to a leaf, one per depth, so that the
// leaves after it read their ancestors' links once (office-floor's 8 rooms: 7.3 M of the leaves' own
// links against 116.8 M of their ancestors', read again for each leaf). One per thread.
struct ChainReadings {
  struct Reading {
    Vec3 sent, reflected, target;
  };
  struct Level {
    uint32_t node = UINT32_MAX;
    std::vector<Reading> links;
  };
  std::vector<Level> levels;  // by the element's depth
};

// The solution over one leaf: what does not depend on the point (per quadrant of the leaf) gathered
// once, and the near element sources kept for the contour formula at each point.
class LeafRadiosity {
 public:
  // A cluster keeps its mean B; a leaf of a transmitting polygon (twin: its twin polygon, else kNoTwin)
  // its mean B plus how the punctual lights' irradiance at the point departs, on either side, from
  // what the solve took for it there (the leaf's D; the twin's D at the leaf's place), times ρ and τ.
  // chain: the readings of the last leaf's ancestors, reused where this leaf shares them (optional).
  LeafRadiosity(const ClusterGather& clusters, uint32_t leaf, uint32_t twin = kNoTwin, ChainReadings* chain = nullptr);

  // B at a point of the leaf; gathered: without direct light (the final gather adds it).
  Vec3 at(const Vec3& x, bool gathered = false) const;

 private:
  // A source's unoccluded form factor from x and what it brings there (sent × F), part by part where
  // the source is a close leaf with resolved parts (ClusterGather::resolve_close_sources).
  void source_at(uint32_t node, const Vec3& x, const Vec3& normal, const Vec3& sent, Vec3& H, double& f) const;

  // Σ over a near source's parts down to where the point is no longer close to them: each part's
  // point form factor to x and what it sends (ClusterGather::sent), added to H and f.
  void near_parts(uint32_t node, const Vec3& x, const Vec3& normal, bool gathered, Vec3& H, double& f) const;

  struct Near {
    uint32_t source;
    double visible;  // F / F_open of the link
    bool close;      // near enough for the point's form factor at every vertex (else at gathered ones only)
    Vec3 sent, reflected;  // what the link takes from the source (ClusterGather::sent)
    Vec3 target;           // where visible_at's rays end (seen in part, rays given): the source's centre, lifted
  };
  // At a gathered point: whether it sees a source its link saw in part (else the link's fraction).
  double visible_at(const Near& s, const Vec3& x) const;
  // Where the punctual lights' and the sky's rays leave x from: lifted off the leaf and moved towards its
  // centre (as the final gather's), so that a vertex in a room's corner, on the walls' planes too,
  // casts no ray that slips behind them.
  Vec3 ray_origin(const Vec3& x) const;
  const ClusterGather& clusters_;
  const Hierarchy& h_;
  uint32_t leaf_;
  bool flat_;
  bool lit_sides_ = false;  // transmitting, with punctual lights: their variation on both sides
  Vec3 tau_, D_front_, D_back_;
  std::array<Polygon, 4> quadrants_;
  std::array<Vec3, 4> H_{};   // by the shares: every source but those near
  std::array<Vec3, 4> Hg_{};  // gathered: what the sources not taken at the point reflect
  std::array<double, 4> row_{}, rowg_{};
  std::vector<Near> near_;
};

}  // namespace walkrad
