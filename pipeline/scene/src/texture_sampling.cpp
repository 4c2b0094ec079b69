#include "walkrad/scene/texture_sampling.h"

#include <algorithm>

#include "walkrad/core/sampling.h"

namespace walkrad {

namespace {

// The texture's mean over the element relative to its mean over the whole image, per channel.
Vec3 relative_mean(const Texture& t, const Polygon& element) {
  constexpr int kN = 8;
  Vec3 sum;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      const Vec3 p = sample_polygon(element, (i + 0.5) / kN, (j + 0.5) / kN);
      sum += t.at(element.uv.u(p), element.uv.v(p));
    }
  const Vec3 mean = sum / double(kN * kN);
  Vec3 r;
  for (int c = 0; c < 3; ++c) r[c] = t.mean[c] > 0 ? mean[c] / t.mean[c] : 0.0;
  return r;
}

}  // namespace

SurfaceColour element_colour(const Scene& scene, const Polygon& element) {
  const Material& m = scene.materials[element.material];
  SurfaceColour c{m.reflectance, m.emission};
  if (!element.uv.valid) return c;
  if (m.reflectance_texture >= 0) {
    c.reflectance = mul(m.reflectance, relative_mean(scene.textures[size_t(m.reflectance_texture)], element));
    for (int k = 0; k < 3; ++k) c.reflectance[k] = std::clamp(c.reflectance[k], 0.0, std::min(0.99, 1.0 - m.transmittance[k]));
  }
  if (m.emission_texture >= 0) c.emission = mul(m.emission, relative_mean(scene.textures[size_t(m.emission_texture)], element));
  return c;
}

bool has_textures(const Scene& scene) {
  for (const Polygon& p : scene.polygons) {
    const Material& m = scene.materials[p.material];
    if (p.uv.valid && (m.reflectance_texture >= 0 || m.emission_texture >= 0)) return true;
  }
  return false;
}

}  // namespace walkrad
