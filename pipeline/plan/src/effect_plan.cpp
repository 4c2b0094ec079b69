#include "walkrad/plan/effect_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "walkrad/formats/error.h"
#include "walkrad/core/sampling.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/scene/texture_sampling.h"

namespace walkrad {

namespace {

// Whether some vertex of b lies strictly in front of a's plane.
bool in_front(const Polygon& a, const Vec3& normal, const Polygon& b, double tol) {
  for (int k = 0; k < b.count; ++k)
    if (dot(b.v[k] - a.v[0], normal) > tol) return true;
  return false;
}

// Does a polygon with ρ > 0 face an emitter (each in front of the other's plane) or a punctual light?
bool reflector_faces_light(const Scene& scene, double tol) {
  std::vector<size_t> emitters;
  for (size_t i = 0; i < scene.polygons.size(); ++i)
    if (scene.materials[scene.polygons[i].material].emits()) emitters.push_back(i);
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    if (luminance(scene.materials[p.material].reflectance) <= 0) continue;
    const Vec3 n = polygon_normal(p);
    for (const PunctualLight& l : scene.lights)
      if (l.type == PunctualLight::Type::sky ||
          (l.type == PunctualLight::Type::directional ? dot(l.direction, n) < 0 : dot(l.position - p.v[0], n) > tol))
        return true;
    for (size_t e : emitters) {
      const Polygon& l = scene.polygons[e];
      if (e != i && in_front(p, n, l, tol) && in_front(l, polygon_normal(l), p, tol)) return true;
    }
  }
  return false;
}

}  // namespace

void apply_override(Effect& e, const std::string& name, const std::map<std::string, std::string>& overrides) {
  const auto it = overrides.find(name);
  if (it == overrides.end()) return;
  e.on = it->second == "on";
  e.forced = true;
  e.reason = "forced " + it->second + " (--effect " + name + "=" + it->second + "); the analysis said: " + e.reason;
}

namespace {

nlohmann::json effect_json(const Effect& e) { return {{"on", e.on}, {"reason", e.reason}, {"forced", e.forced}}; }

}  // namespace

bool is_convex_enclosure(const Scene& scene) {
  const double tol = 1e-9 * std::max(length(scene.bounds().diagonal()), 1e-30);
  for (const Polygon& a : scene.polygons) {
    const Vec3 n = polygon_normal(a);
    for (const Polygon& b : scene.polygons)
      for (int k = 0; k < b.count; ++k)
        if (dot(b.v[k] - a.v[0], n) < -tol) return false;  // behind a: a could hide it from something
  }
  return true;
}

namespace {

// The polygons pressed against others: for each, those that face the other way in its plane and meet
// its box, found the first time one of its rays escapes or meets a back face, among the polygons the
// scene's cluster tree (cluster_tree.h) finds near its box. (A pass over the whole scene for each such
// polygon grew as the square of the polygons: office-floor's prepare phase took 5.3 s at 32 rooms,
// 27.4 s at 64.)
class PressedFaces {
 public:
  PressedFaces(const Scene& scene, double tol, const ClusterTree* tree)
      : scene_(scene), tol_(tol), found_(scene.polygons.size(), 0), opposite_(scene.polygons.size()), given_(tree) {
    normals_.reserve(scene.polygons.size());
    for (const Polygon& p : scene.polygons) normals_.push_back(polygon_normal(p));
  }
  const Vec3& normal(size_t i) const { return normals_[i]; }

  // Whether point p of polygon `self` lies on a polygon that faces the other way in the same plane:
  // the two are pressed together (a table's bottom on the floor) and p sees nothing at all, so a ray
  // from it proves nothing about openings. Polygons are convex (contact_split.h keeps them so).
  bool at(size_t self, const Vec3& p) {
    if (!found_[self]) {
      found_[self] = 1;
      const Vec3& n = normals_[self];
      const Polygon& own = scene_.polygons[self];
      for (const uint32_t j : meeting(uint32_t(self))) {
        const Polygon& q = scene_.polygons[j];
        if (j == self || dot(normals_[j], n) > -1 + 1e-9 || std::fabs(dot(own.v[0] - q.v[0], normals_[j])) > tol_) continue;
        opposite_[self].push_back(j);
      }
    }
    for (const uint32_t j : opposite_[self]) {
      const Polygon& q = scene_.polygons[j];
      const Vec3& m = normals_[j];
      if (std::fabs(dot(p - q.v[0], m)) > tol_) continue;
      bool inside = true;
      for (int k = 0; k < q.count && inside; ++k) {
        const Vec3 a = q.v[k], e = q.v[(k + 1) % q.count] - a;
        const double len = length(e);
        inside = !(len > 0 && dot(cross(e, p - a), m) < -tol_ * len);
      }
      if (inside) return true;
    }
    return false;
  }

 private:
  // The polygons whose boxes meet polygon i's within tol, in index order (without a tree given, one
  // made at the first search: most scenes never search).
  const std::vector<uint32_t>& meeting(uint32_t i) {
    if (!given_ && !made_) made_ = std::make_unique<ClusterTree>(build_cluster_tree(scene_));
    const ClusterTree& tree = given_ ? *given_ : *made_;
    const Bounds& own = tree.polygon_bounds[i];
    auto apart = [&](const Bounds& b) {
      for (int k = 0; k < 3; ++k)
        if (b.lo[k] > own.hi[k] + tol_ || b.hi[k] < own.lo[k] - tol_) return true;
      return false;
    };
    near_.clear();
    std::vector<int32_t> stack;
    if (!tree.nodes.empty()) stack.push_back(0);
    while (!stack.empty()) {  // a node's box holds its polygons': apart from it, apart from them
      const ClusterNode& node = tree.nodes[size_t(stack.back())];
      stack.pop_back();
      if (apart(node.bounds)) continue;
      if (!node.leaf()) {
        stack.push_back(node.child[0]);
        stack.push_back(node.child[1]);
        continue;
      }
      for (uint32_t k = node.first; k < node.first + node.count; ++k)
        if (!apart(tree.polygon_bounds[tree.polygons[k]])) near_.push_back(tree.polygons[k]);
    }
    std::sort(near_.begin(), near_.end());
    return near_;
  }

  const Scene& scene_;
  double tol_;
  std::vector<Vec3> normals_;
  std::vector<uint8_t> found_;
  std::vector<std::vector<uint32_t>> opposite_;
  const ClusterTree* given_;
  std::unique_ptr<ClusterTree> made_;
  std::vector<uint32_t> near_;
};

}  // namespace

std::vector<int> channels_without_absorption(const Scene& scene) {
  std::vector<bool> used(scene.materials.size(), false);
  for (const Polygon& p : scene.polygons) used[p.material] = true;
  std::vector<int> channels;
  for (int c = 0; c < 3; ++c) {
    bool absorbs = false;
    for (size_t m = 0; m < used.size() && !absorbs; ++m)
      absorbs = used[m] && scene.materials[m].reflectance[c] + scene.materials[m].transmittance[c] < 1;
    if (!absorbs && !scene.polygons.empty()) channels.push_back(c);
  }
  return channels;
}

bool is_closed(const Scene& scene, const RayScene& rays, uint64_t& rays_cast, uint64_t& pressed_samples, double* back_share,
               const ClusterTree* tree) {
  const size_t n = scene.polygons.size();
  const double tol = 1e-6 * length(scene.bounds().diagonal());  // contact_split's default
  PressedFaces pressed(scene, tol, tree);
  const size_t per = std::clamp<size_t>(65536 / std::max<size_t>(n, 1), 1, 64);
  double total = 0, lost = 0;
  for (const Polygon& p : scene.polygons) total += polygon_area(p);
  if (back_share) *back_share = 0;
  for (size_t i = 0; i < n; ++i) {
    const Polygon& p = scene.polygons[i];
    const Vec3 normal = pressed.normal(i);
    const double share = polygon_area(p) / double(per);  // of the area, each ray from p
    Rng rng(i, 0x636c6f73ull);  // "clos"
    for (size_t k = 0; k < per; ++k) {
      const double v = rng.uniform(), u = rng.uniform();  // named: argument order is unspecified (GCC's kept)
      const Vec3 origin = sample_polygon(p, u, v) + normal * rays.offset();
      const Vec3 d = cosine_direction(normal, rng);
      ++rays_cast;
      const RayScene::Hit hit = rays.intersect(origin, d);
      if (hit.hit && dot(d, pressed.normal(hit.polygon)) <= 0) continue;  // a front face: the light stays
      if (pressed.at(i, origin - normal * rays.offset())) {
        ++pressed_samples;
        continue;
      }
      if (!hit.hit) return false;
      // A back face (none coincident in front of it: RayScene::intersect) absorbs what reaches it.
      lost += share;
      if (back_share) *back_share = total > 0 ? lost / total : 0.0;
      if (lost > kClosedBackShare * total) return false;
    }
  }
  return n > 0;
}

EffectPlan plan_effects(const Scene& scene, const RayScene& rays, const std::vector<Viewpoint>& views,
                        bool view_independent, Method method,
                        const std::map<std::string, std::string>& overrides, const VolumeClusters* volumes,
                        const ClusterTree* tree) {
  for (const auto& [name, value] : overrides) {
    if (name != "indirect" && name != "visibility" && name != "importance" && name != "clusters" && name != "closure" &&
        name != "punctual" && name != "transmission" && name != "textures" && name != "volumes" && name != "gather" &&
        name != "discontinuities")
      throw InputError("--effect", name,
                       "unknown effect (known: indirect, visibility, importance, clusters, closure, punctual, transmission, "
                       "textures, volumes, gather, discontinuities)",
                       kExitBadArguments);
    if (value != "on" && value != "off")
      throw InputError("--effect", name, "expected on or off, not '" + value + "'", kExitBadArguments);
  }
  const double tol = 1e-9 * std::max(length(scene.bounds().diagonal()), 1e-30);
  EffectPlan plan;
  plan.indirect.on = reflector_faces_light(scene, tol);
  plan.indirect.reason = plan.indirect.on ? "surfaces with reflectance > 0 face an emitter"
                                          : "no surface that light reaches reflects (ρ = 0): direct light only, B = E + one gather";
  // A light outside the enclosure (behind a wall's plane) is hidden from the opposite walls by it.
  bool lights_inside = true;
  for (const PunctualLight& l : scene.lights) {
    // The sun and the sky: outside everything.
    if (l.type == PunctualLight::Type::directional || l.type == PunctualLight::Type::sky) lights_inside = false;
    for (size_t i = 0; i < scene.polygons.size() && lights_inside; ++i)
      lights_inside = dot(l.position - scene.polygons[i].v[0], polygon_normal(scene.polygons[i])) >= -tol;
  }
  const bool convex = is_convex_enclosure(scene);  // O(n²): once
  plan.visibility.on = !convex || !lights_inside;
  plan.visibility.reason = !convex ? "some polygon lies behind another's plane: occlusion is possible"
                           : plan.visibility.on ? "a punctual light stands outside the convex enclosure: its walls cast shadows"
                                                : "a convex enclosure with nothing inside: no occlusion possible, no rays";
  size_t points = 0, spots = 0, suns = 0, luminaires = 0;
  std::string sky;  // the sky's description; empty without one
  for (const PunctualLight& l : scene.lights) {
    if (l.type == PunctualLight::Type::sky) {
      if (l.sky) sky = sky_description(*l.sky);
      continue;
    }
    (l.type == PunctualLight::Type::spot          ? spots
     : l.type == PunctualLight::Type::ies         ? luminaires
     : l.type == PunctualLight::Type::directional ? suns
                                                  : points) += 1;
  }
  plan.punctual.on = !scene.lights.empty();
  plan.punctual.reason = plan.punctual.on ? std::to_string(points) + " point, " + std::to_string(spots) + " spot and " +
                                                std::to_string(suns) + " directional lights (KHR_lights_punctual), " +
                                                std::to_string(luminaires) +
                                                " IES luminaires: shot straight to the elements, a shadow ray per sample" +
                                                (suns ? " (towards a directional light, one to each of a pattern of points of its disc)" : "") +
                                                (!sky.empty() ? "; " + sky + " seen through the scene's openings: at each point rays "
                                                                   "over the hemisphere, denser where what the point sees of the sky changes"
                                                       : "")
                                          : "no punctual lights";
  plan.importance.on = !views.empty() && !view_independent;
  plan.importance.reason = views.empty() ? "no viewpoints: view-independent refinement (BF oracle)"
                           : view_independent ? "--view-independent: viewpoints used for exposure only"
                                              : std::to_string(views.size()) + " viewpoints: refinement where they look";
  plan.clusters.on = method == Method::hierarchical;
  plan.clusters.reason = plan.clusters.on ? "hierarchical method: groups of polygons exchange light through cluster links"
                                          : "classic method: element to element only";
  uint64_t closure_rays = 0, pressed_samples = 0;
  double back_share = 0;
  const bool closed = method == Method::hierarchical && is_closed(scene, rays, closure_rays, pressed_samples, &back_share, tree);
  // Closed, the leaves' row and column sums could be balanced to 1 (link_transport.h). Off unless asked
  // for: with clusters pushing by direction and links by their shares, the row sums stay near 1, and
  // the balance, its factors bounded, does not converge on office-floor, makes it less accurate
  // (weighted RMS 7.3% against 5.9%) and takes a third of the solve (see docs/numerics.md).
  plan.closure.on = false;
  plan.closed = closed;
  const std::string pressed_note =
      pressed_samples > 0 ? ", but for " + std::to_string(pressed_samples) + " from faces pressed against others" : "";
  const auto percent = [](double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f%%", 100 * x);
    return std::string(text);
  };
  const std::string back_note = back_share > 0 ? ", " + percent(back_share) + " of the area's rays meet a back face" : "";
  plan.closure.reason = method != Method::hierarchical ? "classic method: its uniform elements' row sums need no correction"
                        : closed ? "closed: no ray from any surface escapes (" + std::to_string(closure_rays) + " rays" +
                                       pressed_note + back_note + "); each leaf's row sum scaled to 1 (--effect closure=on balances rows and sends)"
                        : back_share > kClosedBackShare
                            ? "over " + percent(kClosedBackShare) + " of the rays from the surfaces (by area) meet a back face, "
                              "which absorbs what reaches it: row sums are left as computed"
                            : "rays escape the scene: row sums are left as computed";
  apply_override(plan.indirect, "indirect", overrides);
  apply_override(plan.closure, "closure", overrides);
  apply_override(plan.visibility, "visibility", overrides);
  apply_override(plan.importance, "importance", overrides);
  apply_override(plan.clusters, "clusters", overrides);
  apply_override(plan.punctual, "punctual", overrides);
  plan.transmission = plan_transmission(scene, method, overrides);
  plan.textures.on = has_textures(scene);
  plan.textures.reason = plan.textures.on ? "textured materials with texture coordinates: sampled per element"
                                          : "no textured surface with texture coordinates: each material's average";
  apply_override(plan.textures, "textures", overrides);
  if (plan.textures.on && !has_textures(scene))
    throw InputError("--effect", "textures", "the scene has no textured surface with texture coordinates", kExitBadArguments);
  const bool has_volumes = volumes && !volumes->empty();
  plan.volumes.on = has_volumes && plan.visibility.on && method == Method::hierarchical;
  if (method != Method::hierarchical) {
    plan.volumes.reason = "classic method: exact rays only";
  } else if (!has_volumes) {
    plan.volumes.reason = "no cluster of many small separate objects spread as if at random (a volume): exact rays only";
  } else {
    const size_t n = scene.polygons.size();
    plan.volumes.reason = std::to_string(volumes->boxes.size()) + " volume clusters hold " +
                          std::to_string(volumes->volume_polygons) + " of " + std::to_string(n) +
                          " polygons: links see through them where their objects are smaller than the penumbra";
    if (!plan.visibility.on) plan.volumes.reason += "; but no occlusion is possible here";
  }
  apply_override(plan.volumes, "volumes", overrides);
  if (plan.volumes.on && (!has_volumes || method != Method::hierarchical || !plan.visibility.on))
    throw InputError("--effect", "volumes",
                     method != Method::hierarchical ? "volumetric visibility exists only in the hierarchical method"
                     : !has_volumes           ? "the scene has no volume cluster"
                                              : "visibility is off: there is nothing to see through",
                     kExitBadArguments);
  plan.gather = plan_gather(scene, views, method, overrides);
  plan.discontinuities = plan_discontinuities(scene, plan.gather, plan.visibility, overrides);
  if (plan.transmission.on && !plan.indirect.on && !plan.indirect.forced) {
    plan.indirect.on = true;
    plan.indirect.reason = "light passes through transmitting surfaces: it needs the gather";
  }
  if (plan.punctual.on && scene.lights.empty())
    throw InputError("--effect", "punctual", "the scene has no punctual lights", kExitBadArguments);
  if (plan.importance.on && views.empty())
    throw InputError("--effect", "importance", "importance needs viewpoints (--views or glTF cameras)", kExitBadArguments);
  if (plan.clusters.on && method != Method::hierarchical)
    throw InputError("--effect", "clusters", "clusters exist only in the hierarchical method", kExitBadArguments);
  if (!plan.clusters.on && method == Method::hierarchical)
    throw InputError("--effect", "clusters", "the hierarchical method cannot run without clusters (use --method classic)",
                     kExitBadArguments);
  return plan;
}

nlohmann::json EffectPlan::to_json() const {
  return {{"indirect", effect_json(indirect)}, {"visibility", effect_json(visibility)},
          {"importance", effect_json(importance)}, {"clusters", effect_json(clusters)}, {"closure", effect_json(closure)},
          {"punctual", effect_json(punctual)}, {"transmission", effect_json(transmission)},
          {"textures", effect_json(textures)}, {"volumes", effect_json(volumes)},
          {"gather", effect_json(gather)}, {"discontinuities", effect_json(discontinuities)}};
}

std::string EffectPlan::explain() const {
  std::string out;
  auto line = [&](const char* name, const Effect& e) { out += std::string(name) + ": " + (e.on ? "on" : "off") + " — " + e.reason + "\n"; };
  line("indirect", indirect);
  line("visibility", visibility);
  line("importance", importance);
  line("clusters", clusters);
  line("closure", closure);
  line("punctual", punctual);
  line("transmission", transmission);
  line("textures", textures);
  line("volumes", volumes);
  line("gather", gather);
  line("discontinuities", discontinuities);
  return out;
}

namespace {

size_t emitting_polygons(const Scene& scene) {
  size_t n = 0;
  for (const Polygon& p : scene.polygons) n += scene.materials[p.material].emits() ? 1 : 0;
  return n;
}

}  // namespace

Effect plan_gather(const Scene& scene, const std::vector<Viewpoint>& views, Method method,
                   const std::map<std::string, std::string>& overrides) {
  const size_t emitters = emitting_polygons(scene);
  const size_t lights = scene.lights.size();
  Effect e;
  e.on = emitters + lights > 0 && method == Method::hierarchical && !views.empty();
  const std::string what = emitters > 0 ? std::to_string(emitters) + " emitting polygons" + (lights > 0 ? " and punctual lights" : "")
                                        : std::to_string(lights) + " punctual lights";
  e.reason = method != Method::hierarchical  ? "classic method: vertices take the elements' radiosity"
             : emitters + lights == 0 ? "no emitter: nothing to gather"
             : views.empty()
                 ? "no viewpoints: nothing says which vertices are seen, they keep the solution's values "
                   "(--effect gather=on gathers at every vertex)"
                 : what + ": their direct light evaluated at the vertices of the polygons the viewpoints see (shadow "
                          "rays to each emitter), the nearby surfaces' light at the point, and the mesh split where "
                          "its shading would miss a shadow's edge (the links bring the indirect)";
  apply_override(e, "gather", overrides);
  if (e.on && (emitters + lights == 0 || method != Method::hierarchical))
    throw InputError("--effect", "gather", emitters + lights == 0 ? "the scene has no emitter" : "the final gather exists only in the hierarchical method",
                     kExitBadArguments);
  return e;
}

Effect plan_discontinuities(const Scene& scene, const Effect& gather, const Effect& visibility,
                            const std::map<std::string, std::string>& overrides) {
  const size_t emitters = emitting_polygons(scene);
  Effect e;
  e.on = gather.on && emitters > 0 && visibility.on;
  e.reason = !gather.on      ? "the final gather is off: no vertex takes its direct light at the point"
             : emitters == 0 ? "no emitting polygon: punctual lights cast hard shadows, with no penumbra to follow"
             : !visibility.on
                 ? "visibility is off: nothing casts a shadow"
                 : "the seen faces are cut along the shadow boundaries (penumbra and umbra edges) the " + std::to_string(emitters) +
                       " emitting polygons cast past their occluders, so that the shading bends where the light does";
  apply_override(e, "discontinuities", overrides);
  if (e.on && (!gather.on || emitters == 0))
    throw InputError("--effect", "discontinuities",
                     emitters == 0 ? "the scene has no emitting polygon" : "discontinuity meshing needs the final gather (--effect gather=on)",
                     kExitBadArguments);
  return e;
}

Effect plan_transmission(const Scene& scene, Method method, const std::map<std::string, std::string>& overrides) {
  size_t count = 0;
  for (const Polygon& p : scene.polygons) count += scene.materials[p.material].transmits() ? 1 : 0;
  Effect e;
  e.on = count > 0 && method == Method::hierarchical;
  e.reason = count == 0 ? "no material transmits"
             : method != Method::hierarchical
                 ? std::to_string(count) + " polygons transmit, but the classic method does not simulate transmission (use the hierarchical one)"
                 : std::to_string(count) + " polygons transmit (diffuse transmission): each gets a back-facing twin that passes light through";
  if (!scene.glass.empty()) {
    double lo = INFINITY, hi = 0;
    for (const Polygon& p : scene.glass) lo = std::min(lo, scene.materials[p.material].ior), hi = std::max(hi, scene.materials[p.material].ior);
    char index[64];
    std::snprintf(index, sizeof index, lo == hi ? "%g" : "%g to %g", lo, hi);
    e.reason += "; " + std::to_string(scene.glass.size()) + " polygons of clear glass (index " + index +
                "): rays cross them with a thin pane's Fresnel transmittance times its filter, and what they reflect is dropped";
  }
  apply_override(e, "transmission", overrides);
  if (e.on && (count == 0 || method != Method::hierarchical))
    throw InputError("--effect", "transmission", count == 0 ? "no material transmits" : "the classic method does not simulate transmission",
                     kExitBadArguments);
  return e;
}

}  // namespace walkrad
