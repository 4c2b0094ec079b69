#include "walkrad/plan/back_lit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "walkrad/core/sampling.h"
#include "walkrad/formats/scene_reader.h"

namespace walkrad {

namespace {

struct Light {
  double power = 0;
  int64_t polygon = -1;  // else the punctual light's index in scene.lights, as -2 - index
};

}  // namespace

BackLight light_on_back_faces(const Scene& scene, const RayScene& rays) {
  std::vector<Light> lights;
  double total = 0;
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const double p = polygon_area(scene.polygons[i]) * luminance(scene.materials[scene.polygons[i].material].emission);
    if (p > 0) lights.push_back({p, int64_t(i)});
  }
  for (size_t l = 0; l < scene.lights.size(); ++l) {
    const PunctualLight& light = scene.lights[l];
    // The sun lights a building from outside, where its faces point out; light it sends through windows
    // meets the inside's backs only where the rooms face the wrong way, which the lamps inside show;
    // so does the sky's.
    if (light.type == PunctualLight::Type::directional || light.type == PunctualLight::Type::sky) continue;
    const double cone = light.type == PunctualLight::Type::spot ? light.outer_cone : kPi;
    const double p = 2 * kPi * (1 - std::cos(cone)) * luminance(light.intensity);  // at most (an IES light's peak)
    if (p > 0) lights.push_back({p, -2 - int64_t(l)});
  }
  for (const Light& l : lights) total += l.power;
  BackLight out;
  if (total <= 0) return out;
  // By the file's material: the pieces contact splitting gave a "… (covered)" copy count as their own.
  std::map<std::string, uint32_t> first;
  std::vector<uint32_t> named(scene.materials.size());
  for (uint32_t m = 0; m < scene.materials.size(); ++m) {
    std::string name = scene.materials[m].name;
    const std::string covered = " (covered)";
    if (name.size() > covered.size() && name.compare(name.size() - covered.size(), covered.size(), covered) == 0)
      name.resize(name.size() - covered.size());
    named[m] = first.emplace(name, m).first->second;
  }
  std::map<uint32_t, double> by_material;
  for (size_t k = 0; k < lights.size(); ++k) {
    const Light& l = lights[k];
    const auto n = uint64_t(std::ceil(double(kBackLitRays) * l.power / total));  // at least one a light
    const double each = l.power / total / double(n);
    Rng rng(k, 0x6261636bull);  // "back"
    for (uint64_t r = 0; r < n; ++r) {
      Vec3 origin, d;
      if (l.polygon >= 0) {
        const Polygon& p = scene.polygons[size_t(l.polygon)];
        const Vec3 normal = polygon_normal(p);
        const double u = rng.uniform(), v = rng.uniform();  // named: argument order is unspecified
        origin = sample_polygon(p, u, v) + normal * rays.offset();
        d = cosine_direction(normal, rng);
      } else {
        const PunctualLight& light = scene.lights[size_t(-2 - l.polygon)];
        origin = light.position;
        d = cone_direction(light.type == PunctualLight::Type::spot ? light.direction : Vec3(0, 0, 1),
                    light.type == PunctualLight::Type::spot ? light.outer_cone : kPi, rng);
      }
      ++out.rays;
      const RayScene::Hit hit = rays.intersect(origin, d);
      if (!hit.hit || dot(d, polygon_normal(scene.polygons[hit.polygon])) < 0) continue;  // gone, or a front face
      out.share += each;
      by_material[named[scene.polygons[hit.polygon].material]] += each;
    }
  }
  out.materials.assign(by_material.begin(), by_material.end());
  std::stable_sort(out.materials.begin(), out.materials.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  return out;
}

std::string back_lit_warning(const Scene& scene, const BackLight& b) {
  if (b.share <= kBackLitWarning) return "";
  auto percent = [](double x) {
    char text[16];
    std::snprintf(text, sizeof text, "%.0f%%", 100 * x);
    return std::string(text);
  };
  std::string which;
  for (size_t k = 0; k < b.materials.size() && k < 4; ++k)
    which += (k ? ", " : "") + scene.materials[b.materials[k].first].name + " " + percent(b.materials[k].second);
  if (b.materials.size() > 4) which += ", ...";
  return percent(b.share) + " of the light emitted first meets the back of one-sided polygons (" + which +
         "), which absorb it: they face away from the lights. If they are meant two-sided, " +
         (is_mgf(scene.source) ? "say so (MGF 'sides 2', or --mgf-sides 2 for materials that do not state it)" : "mark them doubleSided");
}

}  // namespace walkrad
