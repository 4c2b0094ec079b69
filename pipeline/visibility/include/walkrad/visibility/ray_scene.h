// RayScene: the input polygons in an Embree 3 BVH, for visibility and primary rays. Polygons go in as
// one quad geometry (a triangle is a quad whose last vertex repeats, as Embree documents), so a hit's
// primID is the polygon's index. The scene is built in robust mode (no ray slips through a shared
// edge), re-centred on its bounds so that float coordinates keep their digits far from the origin, and
// scaled by a power of two to a unit size so that rounding does not depend on the scene's units.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <embree3/rtcore.h>

#include "walkrad/formats/scene.h"

namespace walkrad {

class RayScene {
 public:
  explicit RayScene(const Scene& scene);
  // The scene without the polygons marked in exclude (same coordinates, offsets and rounding as the
  // whole scene's RayScene): hits name the scene's polygon indices.
  RayScene(const Scene& scene, const std::vector<uint8_t>& exclude);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // True if something blocks the open segment from `from` to `to` (end points excluded by the
  // caller's offsets: see offset()).
  bool occluded(const Vec3& from, const Vec3& to) const;

  // Occlusion of many segments at once through Embree's stream interface (rtcOccluded1M, coherent):
  // blocked[k] = 1 if segment k (from[k] → to[k]) is blocked. Not always occluded()'s answer, ray for
  // ray: office-floor's 8 rooms change in a few vertices when the mesher's one-point rays are cast
  // through it, coherent flag or not (which rays differ, and why, is not known).
  struct Segment {
    Vec3 from, to;
  };
  void occluded(const Segment* segments, size_t count, uint8_t* blocked) const;

  struct Hit {
    bool hit = false;
    uint32_t polygon = 0;
    Vec3 position;
  };
  // The first surface along the ray. Where it meets a back face that has a front face coincident
  // with it (within offset(): a wall modelled as two polygons back to back, a doubleSided quad made two
  // polygons), the front face is the hit, whichever of the two Embree met first: every query that
  // shades (reference, bake sampler, exposure, importance) then sees the side that faces it.
  Hit intersect(const Vec3& origin, const Vec3& direction) const;

  // The distance by which ray end points leave their surfaces: small against the scene, large
  // against float rounding at the scene's scale (docs/numerics.md).
  double offset() const { return offset_; }

  // Where the scene has a sky (sky.h), its openings (openings.h), their triangles in a BVH of their
  // own: the sky is sampled through them (sky_light.h). nullptr without a sky, and for a scene built
  // without some of its polygons.
  struct Openings {
    std::vector<Polygon> triangles;
    std::unique_ptr<RayScene> rays;  // hits name indices into triangles
  };
  const Openings* openings() const { return openings_.get(); }

  // Clear glass (Scene::glass, not in the BVH above: it blocks nothing): the product, per channel, of
  // the panes' transmittance along the segment from → to, each its material's filter times
  // pane_transmittance (fresnel.h) at the angle the segment crosses it; (1, 1, 1) where it crosses none.
  Vec3 transmittance(const Vec3& from, const Vec3& to) const;
  bool has_glass() const { return glass_ != nullptr; }

 private:
  void build(const Scene& scene, const std::vector<uint8_t>* exclude);
  void add_quads(const Scene& scene, const std::vector<uint32_t>& polygons);

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  Vec3 origin_;  // subtracted from every coordinate before it reaches Embree
  double scale_ = 1;  // then multiplied by this power of two
  double offset_ = 0;
  std::vector<uint32_t> prim_polygon_;  // with excluded polygons: Embree primitive → polygon
  std::vector<Vec3> prim_normal_;       // each primitive's front (counter-clockwise) normal, unnormalised
  std::unique_ptr<Openings> openings_;
  struct Glass {
    std::unique_ptr<RayScene> rays;  // the panes, hits naming their index
    std::vector<Vec3> filter, normal;
    std::vector<double> ior;
  };
  std::unique_ptr<Glass> glass_;
};

}  // namespace walkrad
