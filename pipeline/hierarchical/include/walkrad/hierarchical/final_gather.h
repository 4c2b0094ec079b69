// The final gather's direct part (the "reconstruction" pass of Lischinski, Tampieri &
// Greenberg 1992; Reichert 1992): at an output vertex the walkthrough sees, the irradiance from every
// area emitter is evaluated at the point instead of taken from the links,
//   D(x) = Σ_e E_e · F(dx → e) · V̄_e(x),
//   V̄_e(x) = Σ_k K(x, y_k) V(x, y_k) / Σ_k K(x, y_k),   K = cos θ_x cos θ_y / r²,
// F the contour formula (exact, form_factor.h) and V̄ the kernel-weighted fraction of the emitter that x
// sees, over stratified points y_k of the emitter: 16 (and its corners), and kVertexPenumbra² more where
// they disagree (a penumbra).
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
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

// Whether a leaf of a seen polygon lies where the walkthrough looks, so that its vertices are gathered:
// it, or its element ancestor of the scene's typical polygon area (`reach`: view_reach), holds view
// hits. A polygon seen at one end (a corridor's 320 m floor through one doorway) is gathered near that
// end only; the rest shows the solution, as unseen surfaces do. Every leaf where the hierarchy holds no
// hits (no importance).
bool in_view(const Hierarchy& h, uint32_t leaf, double reach);
// The median input polygon's area as default_min_area takes it (16,384 times it): a room's wall or floor.
double view_reach(const Hierarchy& h);

// A set of emitters as half-open ranges of DirectGather's emitter indices, sorted and disjoint.
using EmitterRanges = std::vector<std::pair<uint32_t, uint32_t>>;

// Merges b into a (both sorted and disjoint).
void merge_ranges(EmitterRanges& a, const EmitterRanges& b);

// The emitters of `bounds` ((bound, emitter), ascending as DirectGather::bounds gives them) less the
// faintest, left out while the sum of their bounds stays at or below `negligible`.
EmitterRanges without_faintest(const std::vector<std::pair<double, uint32_t>>& bounds, double negligible);

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

  // What each emitter of `from` could give unoccluded, as luminance (emission × the contour form
  // factor, reflectance `rho`), at the most it gives at any of `points` (unit normal n): (bound, emitter),
  // ascending (ties by emitter). Far emitters behind a linked cluster (a wing's lamps past a doorway)
  // would cost every point their shadow rays for light that cannot matter.
  std::vector<std::pair<double, uint32_t>> bounds(const EmitterRanges& from, const Vec3* points, size_t count,
                                                  const Vec3& n, const Vec3& rho) const;
  // The emitters of `from` less the faintest (without_faintest of their bounds).
  EmitterRanges strongest(const EmitterRanges& from, const Vec3* points, size_t count, const Vec3& n, const Vec3& rho,
                          double negligible) const;

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

}  // namespace walkrad
