// The final gather's direct part (issue 23; the "reconstruction" pass of Lischinski, Tampieri &
// Greenberg 1992; Reichert 1992): at an output vertex the walkthrough sees, the irradiance from every
// area emitter is evaluated at the point instead of taken from the links,
//   D(x) = Σ_e E_e · F(dx → e) · V̄_e(x),
//   V̄_e(x) = Σ_k K(x, y_k) V(x, y_k) / Σ_k K(x, y_k),   K = cos θ_x cos θ_y / r²,
// F the contour formula (exact, form_factor.h) and V̄ the kernel-weighted fraction of the emitter that x
// sees, over stratified points y_k of the emitter: 16, and 64 more where they disagree (a penumbra).
// Punctual lights are added at the point as before (punctual_lights.h). The solution then brings only
// indirect light to the vertex (point_radiosity.h: sources send Bt − their emission), so a shadow's edge
// is as sharp as the output mesh, not as the links' shares.
//
// Which emitters: those under the sources of the links (F > 0) on the leaf's chain, its element
// ancestors and its clusters: an emitter the solution found wholly hidden from the leaf is not
// gathered (a light in another room costs no ray).
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "walkrad/hierarchical/error_presets.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

// A set of emitters as half-open ranges of DirectGather's emitter indices, sorted and disjoint.
using EmitterRanges = std::vector<std::pair<uint32_t, uint32_t>>;

// Merges b into a (both sorted and disjoint).
void merge_ranges(EmitterRanges& a, const EmitterRanges& b);

class DirectGather {
 public:
  // lights: punctual lights (null: none); rays: occluders (null: nothing occludes).
  DirectGather(const Hierarchy& h, const std::vector<PunctualLight>* lights, const RayScene* rays);

  struct Emitter {
    Polygon shape;
    Vec3 normal, emission;
    uint32_t polygon;
    std::array<Vec3, 4> inset;  // its corners a hundredth of the way in towards its centre (visible_fraction)
  };
  size_t emitter_count() const { return emitters_.size(); }
  const Emitter& emitter(uint32_t k) const { return emitters_[k]; }
  bool has_lights() const { return lights_ != nullptr; }

  // The emitters that can light a leaf element: under the sources of the links on its chain.
  EmitterRanges candidates(uint32_t leaf) const;

  // Irradiance at x (unit normal n) from the emitters in `from` and every punctual light. inward: a
  // unit direction in the surface towards its faces around x (zero inside them): shadow rays leave
  // from x moved off the surface and along it, so that from a vertex on a crease they do not start on
  // the neighbouring wall's plane. rays_cast counts the shadow rays. An emitter is sampled at 4 × 4
  // stratified points, and where they disagree (a penumbra) at penumbra² more: kVertexPenumbra for
  // what a vertex shows, kTestPenumbra where the adaptive mesh only asks whether to split.
  static constexpr int kVertexPenumbra = 32, kTestPenumbra = 8;
  Vec3 at(const Vec3& x, const Vec3& n, const Vec3& inward, const EmitterRanges& from, uint64_t& rays_cast,
          int penumbra = kVertexPenumbra) const;

 private:
  EmitterRanges ranges_of(const HNode& source) const;
  double visible_fraction(const Vec3& x, const Vec3& n, const Vec3& from, const Emitter& e, int penumbra,
                          uint64_t& rays_cast) const;

  const Hierarchy& h_;
  const std::vector<PunctualLight>* lights_;
  const RayScene* rays_;
  std::vector<Emitter> emitters_;          // in ClusterTree::polygons order: a cluster's are contiguous
  std::vector<uint32_t> emitter_position_; // each emitter's index in ClusterTree::polygons
  std::vector<uint32_t> polygon_emitter_;  // per input polygon: its emitter index, or UINT32_MAX
  std::vector<EmitterRanges> cluster_ranges_;  // per node (clusters only): its links' and its ancestors'
};

// The adaptive output mesh: a gathered leaf whose reflected direct light ρD, evaluated at its edges'
// quarter, half and three-quarter points and its centre, departs from what Gouraud shading interpolates
// between its corners by more than a quarter of its tolerance (e × what it shows: a shadow edge the
// solution's elements do not follow) is split in four, the worst first, and its children are tested
// again, level by level, while the new leaves stay within `budget`. The children take their parent's
// solution (B, factors): they have no links of their own, so the gather at their vertices uses their
// parent's (point_radiosity.h). In a fixed order: deterministic. Returns the splits.
struct GatherRefinement {
  const std::vector<uint8_t>* seen = nullptr;   // per input polygon, 1: gathered (null: all)
  const std::vector<uint32_t>* twins = nullptr; // transmitting polygons (kNoTwin: none): split for both sides' lights
  double error = kDefaultError;                 // relative to what the leaf shows
  double white = 0;                             // the display's white (luminance, W/m²)
  double min_area = 0;                          // no leaf below it
  int max_depth = 16;
  uint64_t budget = 0;                          // new leaves at most
};
uint64_t refine_for_gather(Hierarchy& h, const DirectGather& gather, const GatherRefinement& r, uint64_t& rays_cast);

}  // namespace walkrad
