// The effect plan: before solving, decide from the scene and the walkthrough which light
// transport a bake simulates, and say why, so that a bake pays only for effects the scene has:
//   indirect    — only if a reflecting surface (ρ > 0) faces an emitter; otherwise B = E + one gather;
//   visibility  — only if something can occlude: never in a convex enclosure (every polygon on or in
//                 front of every other polygon's plane, so no segment between two of them crosses a third);
//   importance  — only with viewpoints (and not --view-independent);
//   clusters    — the hierarchical method's cluster links (always with it; none in the classic method);
//   closure     — balance each leaf's gather and send in a closed scene (no ray from any surface
//                 escapes: every form factor row sums to 1; link_transport.h). Off unless forced on: the
//                 plan says whether the scene is closed, and a closed scene's rows alone are scaled to 1;
//   punctual    — point and spot lights (glTF KHR_lights_punctual), shot straight to the elements
//                 (punctual_lights.h); off ignores them;
//   transmission — diffuse transmission where a material transmits (transmission.h; hierarchical
//                 method only);
//   textures    — reflectance and emission textures sampled per element where polygons have texture
//                 coordinates (texture_sampling.h); off: each material's average;
//   volumes     — volumetric visibility through clusters of many small objects (volume_clusters.h,
//                 volume_visibility.h; hierarchical method, with visibility): only if the scene has such
//                 clusters; off: exact rays everywhere;
//   gather      — the final gather (final_gather.h): area emitters' direct light evaluated at the output
//                 vertices of the polygons the viewpoints see (hierarchical method, with viewpoints;
//                 forced on without them, at every vertex).
//   discontinuities — with the gather, emitting polygons and visibility: the seen faces cut along the
//                 emitters' shadow boundaries (discontinuity_mesh.h, output stage).
// Indirect light and visibility take punctual lights into account (a reflector in front of one; a
// light outside a convex enclosure).
// Each choice can be forced on or off (`walkrad bake --effect NAME=on|off`); `--explain` prints the plan,
// and manifest.json and report.json keep it.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "walkrad/plan/method.h"
#include "walkrad/formats/scene.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/visibility/volume_clusters.h"

namespace walkrad {

struct Effect {
  bool on = true;
  std::string reason;
  bool forced = false;  // by an override
};

struct EffectPlan {
  Effect indirect, visibility, importance, clusters, closure, punctual, transmission, textures, volumes, gather,
      discontinuities;
  bool closed = false;  // no ray from any surface escapes (hierarchical method only): rows scaled to 1
  nlohmann::json to_json() const;
  std::string explain() const;  // one line per effect
};

// overrides: effect name → "on" or "off" (InputError naming --effect for an unknown name or value).
// volumes: the scene's volume clusters (null: none looked for). tree: the scene's cluster tree, for
// is_closed (null: it makes its own where it needs one).
EffectPlan plan_effects(const Scene& scene, const RayScene& rays, const std::vector<Viewpoint>& views,
                        bool view_independent, Method method,
                        const std::map<std::string, std::string>& overrides, const VolumeClusters* volumes = nullptr,
                        const ClusterTree* tree = nullptr);

// The gather entry: on where the hierarchical method meets an emitting polygon and viewpoints; overrides as
// plan_effects'.
Effect plan_gather(const Scene& scene, const std::vector<Viewpoint>& views, Method method,
                   const std::map<std::string, std::string>& overrides);

// The discontinuities entry: on with the gather where emitting polygons can be occluded; overrides as
// plan_effects'.
Effect plan_discontinuities(const Scene& scene, const Effect& gather, const Effect& visibility,
                            const std::map<std::string, std::string>& overrides);

// Applies an --effect override (NAME → "on" or "off", already checked) to e: forced, with the analysis's
// reason kept.
void apply_override(Effect& e, const std::string& name, const std::map<std::string, std::string>& overrides);

// Whether every polygon lies on or in front of every other polygon's plane (tolerance relative to the
// scene's size): then nothing can stand between two surfaces.
bool is_convex_enclosure(const Scene& scene);

// Whether no light leaves the scene: cosine-distributed rays from stratified points of every polygon
// (about 65,536 in all, at least one a polygon), each must hit a surface, but for rays from points
// pressed against a polygon facing the other way in the same plane (a table's bottom on the floor:
// counted in pressed_samples), which see nothing. A ray that meets a back face is lost as surely (a
// one-sided polygon absorbs from behind): the rays from at most kClosedBackShare of the surfaces' area
// may (the floor under a book with no bottom face), a larger share opens the scene (MGF office3, whose
// polygons are one-sided: 23%; scaled to 1, its rows made it 8.8% too bright). back_share: that share,
// as far as the test went. tree: the scene's cluster tree, which finds the polygons a point may be
// pressed against (null: one is made at the first such search). Deterministic.
inline constexpr double kClosedBackShare = 0.05;
bool is_closed(const Scene& scene, const RayScene& rays, uint64_t& rays_cast, uint64_t& pressed_samples,
               double* back_share = nullptr, const ClusterTree* tree = nullptr);

// The colour channels (0 red, 1 green, 2 blue) in which no polygon absorbs: ρ + τ ≥ 1 on every one.
// In a closed scene such a channel has no finite radiosity (each bounce returns all the light: the
// Neumann series Σ (ρF)ᵏ diverges), so the bake refuses it; where light escapes, it has one.
std::vector<int> channels_without_absorption(const Scene& scene);

// The transmission entry: on when a polygon's material transmits and the method is hierarchical;
// overrides as plan_effects' ("transmission" → "on" or "off").
Effect plan_transmission(const Scene& scene, Method method, const std::map<std::string, std::string>& overrides);

}  // namespace walkrad
