// Test helper: what a viewpoint sees of a bake's physical radiosity (_RADIOSITY, interpolated across
// each triangle as a viewer interpolates COLOR_0), by Embree primary rays. Comparing two bakes through
// the same view measures the error where the walkthrough looks, whatever their meshes.
#pragma once

#include <cmath>
#include <vector>

#include "walkrad/formats/chunk.h"
#include "walkrad/pipeline/exposure.h"
#include "walkrad/pipeline/ray_scene.h"

namespace walkrad::test {

// Luminance of B per pixel (grid × grid), NaN where the ray escapes.
inline std::vector<double> radiosity_image(const ChunkMesh& mesh, const Viewpoint& view, int grid) {
  Scene s;
  s.materials.push_back({"m", {0.5, 0.5, 0.5}, {0, 0, 0}});
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    Polygon p;
    p.count = 3;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + k];
      p.v[k] = {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
    }
    s.polygons.push_back(p);
  }
  const RayScene rays(s);
  std::vector<double> image;
  for (int y = 0; y < grid; ++y)
    for (int x = 0; x < grid; ++x) {
      const Vec3 d = view_ray_direction(view, 2.0 * (x + 0.5) / grid - 1.0, 2.0 * (y + 0.5) / grid - 1.0);
      const RayScene::Hit hit = rays.intersect(view.position, d);
      if (!hit.hit) {
        image.push_back(NAN);
        continue;
      }
      // Barycentric interpolation of the triangle's vertex radiosity.
      const Polygon& p = s.polygons[hit.polygon];
      const Vec3 n = cross(p.v[1] - p.v[0], p.v[2] - p.v[0]);
      const double a = dot(cross(p.v[2] - p.v[1], hit.position - p.v[1]), n) / dot(n, n);
      const double b = dot(cross(p.v[0] - p.v[2], hit.position - p.v[2]), n) / dot(n, n);
      const double w[3] = {a, b, 1 - a - b};
      Vec3 B;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = mesh.indices[3 * hit.polygon + k];
        B += Vec3(mesh.radiosity[3 * v], mesh.radiosity[3 * v + 1], mesh.radiosity[3 * v + 2]) * w[k];
      }
      image.push_back(luminance(B));
    }
  return image;
}

// Relative RMS difference of two radiosity images (pixels both hit, emitters left out by a cap).
inline double relative_rms(const std::vector<double>& a, const std::vector<double>& reference, double cap) {
  double num = 0, den = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i]) || std::isnan(reference[i]) || reference[i] > cap) continue;
    num += (a[i] - reference[i]) * (a[i] - reference[i]);
    den += reference[i] * reference[i];
  }
  return std::sqrt(num / den);
}

}  // namespace walkrad::test
