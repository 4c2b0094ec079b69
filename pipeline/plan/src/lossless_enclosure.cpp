#include "walkrad/plan/lossless_enclosure.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "walkrad/core/sampling.h"
#include "walkrad/formats/scene_reader.h"
#include "walkrad/scene/transmission_twins.h"

namespace walkrad {

namespace {

double kept(const Material& m, int c, bool transmits) { return m.reflectance[c] + (transmits ? m.transmittance[c] : 0.0); }

// The polygon a ray meets if it meets a front face, else -1 (escaped, or a back face: absorbed).
int64_t front_hit(const Scene& scene, const RayScene& rays, const Vec3& origin, const Vec3& d) {
  const RayScene::Hit hit = rays.intersect(origin, d);
  if (!hit.hit || dot(d, polygon_normal(scene.polygons[hit.polygon])) >= 0) return -1;
  return hit.polygon;
}

// The channel's enclosures: rays from its lossless polygons, leaks spread back along them.
std::vector<LosslessEnclosure> enclosures_in(const Scene& scene, const RayScene& rays, const std::vector<uint32_t>& twins,
                                             int c) {
  const size_t n = scene.polygons.size();
  const bool transmits = !twins.empty();
  std::vector<uint8_t> lossless(n, 0), leaks(n, 0);
  for (size_t i = 0; i < n; ++i) lossless[i] = kept(scene.materials[scene.polygons[i].material], c, transmits) >= 1;
  std::vector<std::vector<uint32_t>> sees(n);  // the lossless polygons each lossless one's light reaches
  for (size_t i = 0; i < n; ++i) {
    if (!lossless[i]) continue;
    const Polygon& p = scene.polygons[i];
    if (transmits && twins[i] != kNoTwin && scene.materials[p.material].transmittance[c] > 0) sees[i].push_back(twins[i]);
    const Vec3 normal = polygon_normal(p);
    Rng rng(i, 0x6c6f7373ull);  // "loss"
    for (int k = 0; k < kEnclosureRays && !leaks[i]; ++k) {
      const double u = rng.uniform(), v = rng.uniform();  // named: argument order is unspecified
      const Vec3 origin = sample_polygon(p, u, v) + normal * rays.offset();
      const int64_t hit = front_hit(scene, rays, origin, cosine_direction(normal, rng));
      if (hit < 0 || !lossless[size_t(hit)]) leaks[i] = 1;
      else sees[i].push_back(uint32_t(hit));
    }
  }
  // A polygon whose light reaches a leaking one leaks too: spread until nothing changes.
  std::vector<std::vector<uint32_t>> seen_by(n);
  for (size_t i = 0; i < n; ++i)
    for (uint32_t j : sees[i]) seen_by[j].push_back(uint32_t(i));
  std::vector<uint32_t> stack;
  for (size_t i = 0; i < n; ++i)
    if (lossless[i] && leaks[i]) stack.push_back(uint32_t(i));
  while (!stack.empty()) {
    const uint32_t j = stack.back();
    stack.pop_back();
    for (uint32_t i : seen_by[j])
      if (!leaks[i]) {
        leaks[i] = 1;
        stack.push_back(i);
      }
  }
  // What is left, grouped by the rays between them (either way).
  std::vector<int64_t> group(n, -1);
  std::vector<LosslessEnclosure> out;
  for (size_t s = 0; s < n; ++s) {
    if (!lossless[s] || leaks[s] || group[s] >= 0) continue;
    LosslessEnclosure e;
    e.channel = c;
    group[s] = int64_t(out.size());
    stack.assign(1, uint32_t(s));
    while (!stack.empty()) {
      const uint32_t i = stack.back();
      stack.pop_back();
      e.polygons.push_back(i);
      e.lit = e.lit || scene.materials[scene.polygons[i].material].emission[c] > 0;
      for (const auto* next : {&sees[i], &seen_by[i]})
        for (uint32_t j : *next)
          if (group[j] < 0) {
            group[j] = group[s];
            stack.push_back(j);
          }
    }
    std::sort(e.polygons.begin(), e.polygons.end());
    out.push_back(std::move(e));
  }
  for (size_t l = 0; l < scene.lights.size() && !out.empty(); ++l) {
    // Infinitely far, the sun and the sky are inside no enclosure.
    if (scene.lights[l].intensity[c] <= 0 || scene.lights[l].type == PunctualLight::Type::directional ||
        scene.lights[l].type == PunctualLight::Type::sky)
      continue;
    Rng rng(l, 0x6c697465ull);  // "lite"
    int64_t inside = -2;  // the enclosure every ray met so far; -1: none
    for (int k = 0; k < kEnclosureRays && inside != -1; ++k) {
      const int64_t hit = front_hit(scene, rays, scene.lights[l].position, cone_direction(Vec3(0, 0, 1), kPi, rng));
      const int64_t g = hit < 0 ? -1 : group[size_t(hit)];
      inside = inside == -2 || inside == g ? g : -1;
    }
    if (inside >= 0) {
      out[size_t(inside)].lights.push_back(uint32_t(l));
      out[size_t(inside)].lit = true;
    }
  }
  return out;
}

}  // namespace

std::vector<LosslessEnclosure> find_lossless_enclosures(const Scene& scene, const RayScene& rays,
                                                        const std::vector<uint32_t>& twins) {
  std::vector<LosslessEnclosure> all;
  for (int c = 0; c < 3; ++c) {
    std::vector<LosslessEnclosure> found = enclosures_in(scene, rays, twins, c);
    all.insert(all.end(), std::make_move_iterator(found.begin()), std::make_move_iterator(found.end()));
  }
  return all;
}

std::string describe_polygons(const Scene& scene, const std::vector<uint32_t>& polygons, size_t most) {
  std::set<uint32_t> materials, sources;
  for (uint32_t i : polygons) {
    materials.insert(scene.polygons[i].material);
    sources.insert(scene.polygons[i].source);
  }
  const bool mgf = is_mgf(scene.source);
  std::string text = std::to_string(polygons.size()) + (polygons.size() == 1 ? " polygon (material" : " polygons (material");
  text += materials.size() == 1 ? " " : "s ";
  size_t k = 0;
  for (uint32_t m : materials) text += (k++ ? ", '" : "'") + scene.materials[m].name + "'";
  text += mgf ? "; MGF line" : "; glTF mesh";
  text += sources.size() == 1 ? " " : "s ";
  k = 0;
  for (uint32_t s : sources) {
    if (k == most) {
      text += ", ...";
      break;
    }
    text += (k++ ? ", " : "") + std::to_string(s);
  }
  return text + ")";
}

}  // namespace walkrad
