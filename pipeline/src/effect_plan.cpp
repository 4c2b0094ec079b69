#include "walkrad/pipeline/effect_plan.h"

#include <algorithm>

#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

// Whether some vertex of b lies strictly in front of a's plane.
bool in_front(const Polygon& a, const Vec3& normal, const Polygon& b, double tol) {
  for (int k = 0; k < b.count; ++k)
    if (dot(b.v[k] - a.v[0], normal) > tol) return true;
  return false;
}

// Does a polygon with ρ > 0 face an emitter (each in front of the other's plane)?
bool reflector_faces_light(const Scene& scene, double tol) {
  std::vector<size_t> emitters;
  for (size_t i = 0; i < scene.polygons.size(); ++i)
    if (scene.materials[scene.polygons[i].material].emits()) emitters.push_back(i);
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    if (luminance(scene.materials[p.material].reflectance) <= 0) continue;
    const Vec3 n = polygon_normal(p);
    for (size_t e : emitters) {
      const Polygon& l = scene.polygons[e];
      if (e != i && in_front(p, n, l, tol) && in_front(l, polygon_normal(l), p, tol)) return true;
    }
  }
  return false;
}

void apply(Effect& e, const std::string& name, const std::map<std::string, std::string>& overrides) {
  const auto it = overrides.find(name);
  if (it == overrides.end()) return;
  e.on = it->second == "on";
  e.forced = true;
  e.reason = "forced " + it->second + " (--effect " + name + "=" + it->second + "); the analysis said: " + e.reason;
}

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

EffectPlan plan_effects(const Scene& scene, const std::vector<Viewpoint>& views, bool view_independent,
                        const std::string& method, const std::map<std::string, std::string>& overrides) {
  for (const auto& [name, value] : overrides) {
    if (name != "indirect" && name != "visibility" && name != "importance" && name != "clusters")
      throw InputError("--effect", name, "unknown effect (known: indirect, visibility, importance, clusters)", kExitBadArguments);
    if (value != "on" && value != "off")
      throw InputError("--effect", name, "expected on or off, not '" + value + "'", kExitBadArguments);
  }
  const double tol = 1e-9 * std::max(length(scene.bounds().diagonal()), 1e-30);
  EffectPlan plan;
  plan.indirect.on = reflector_faces_light(scene, tol);
  plan.indirect.reason = plan.indirect.on ? "surfaces with reflectance > 0 face an emitter"
                                          : "no surface that light reaches reflects (ρ = 0): direct light only, B = E + one gather";
  plan.visibility.on = !is_convex_enclosure(scene);
  plan.visibility.reason = plan.visibility.on ? "some polygon lies behind another's plane: occlusion is possible"
                                              : "a convex enclosure with nothing inside: no occlusion possible, no rays";
  plan.importance.on = !views.empty() && !view_independent;
  plan.importance.reason = views.empty() ? "no viewpoints: view-independent refinement (BF oracle)"
                           : view_independent ? "--view-independent: viewpoints used for exposure only"
                                              : std::to_string(views.size()) + " viewpoints: refinement where they look";
  plan.clusters.on = method == "hierarchical";
  plan.clusters.reason = plan.clusters.on ? "hierarchical method: groups of polygons exchange light through cluster links"
                                          : "classic method: element to element only";
  apply(plan.indirect, "indirect", overrides);
  apply(plan.visibility, "visibility", overrides);
  apply(plan.importance, "importance", overrides);
  apply(plan.clusters, "clusters", overrides);
  if (plan.importance.on && views.empty())
    throw InputError("--effect", "importance", "importance needs viewpoints (--views or glTF cameras)", kExitBadArguments);
  if (plan.clusters.on && method != "hierarchical")
    throw InputError("--effect", "clusters", "clusters exist only in the hierarchical method", kExitBadArguments);
  if (!plan.clusters.on && method == "hierarchical")
    throw InputError("--effect", "clusters", "the hierarchical method cannot run without clusters (use --method classic)",
                     kExitBadArguments);
  return plan;
}

nlohmann::json EffectPlan::to_json() const {
  return {{"indirect", effect_json(indirect)}, {"visibility", effect_json(visibility)},
          {"importance", effect_json(importance)}, {"clusters", effect_json(clusters)}};
}

std::string EffectPlan::explain() const {
  std::string out;
  auto line = [&](const char* name, const Effect& e) { out += std::string(name) + ": " + (e.on ? "on" : "off") + " — " + e.reason + "\n"; };
  line("indirect", indirect);
  line("visibility", visibility);
  line("importance", importance);
  line("clusters", clusters);
  return out;
}

}  // namespace walkrad
