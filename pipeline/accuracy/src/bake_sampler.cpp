#include "walkrad/accuracy/bake_sampler.h"

#include <cmath>

#include "walkrad/formats/bake_folder.h"
#include "walkrad/visibility/exposure.h"

namespace walkrad {

BakeSampler::BakeSampler(ChunkMesh mesh) : mesh_(std::move(mesh)) {
  triangles_.materials.push_back({"bake", {0.5, 0.5, 0.5}, {0, 0, 0}});
  triangles_.polygons.reserve(mesh_.triangle_count());
  for (size_t t = 0; t < mesh_.triangle_count(); ++t) {
    Polygon p;
    p.count = 3;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh_.indices[3 * t + k];
      p.v[k] = {mesh_.positions[3 * v], mesh_.positions[3 * v + 1], mesh_.positions[3 * v + 2]};
    }
    triangles_.polygons.push_back(p);
  }
  rays_ = std::make_unique<RayScene>(triangles_);
}

BakeSampler BakeSampler::open(const std::string& bake_dir) { return BakeSampler(read_bake_mesh(bake_dir)); }

BakeSampler::Sample BakeSampler::along(const Vec3& origin, const Vec3& unit_direction) const {
  Sample s;
  const RayScene::Hit hit = rays_->intersect(origin, unit_direction);
  if (!hit.hit) return s;
  s.hit = true;
  s.distance = length(hit.position - origin);
  // Barycentric interpolation of the triangle's vertex radiosity.
  const Polygon& p = triangles_.polygons[hit.polygon];
  const Vec3 n = cross(p.v[1] - p.v[0], p.v[2] - p.v[0]);
  const double nn = dot(n, n);
  if (!(nn > 0)) return s;
  const double a = dot(cross(p.v[2] - p.v[1], hit.position - p.v[1]), n) / nn;
  const double b = dot(cross(p.v[0] - p.v[2], hit.position - p.v[2]), n) / nn;
  const double w[3] = {a, b, 1 - a - b};
  for (int k = 0; k < 3; ++k) {
    const uint32_t v = mesh_.indices[3 * hit.polygon + k];
    s.B += Vec3(mesh_.radiosity[3 * v], mesh_.radiosity[3 * v + 1], mesh_.radiosity[3 * v + 2]) * w[k];
  }
  return s;
}

std::vector<double> BakeSampler::luminance_image(const Viewpoint& view, int grid) const {
  std::vector<double> image;
  image.reserve(size_t(grid) * size_t(grid));
  for (int y = 0; y < grid; ++y)
    for (int x = 0; x < grid; ++x) {
      const Sample s = along(view.position, view_ray_direction(view, 2.0 * (x + 0.5) / grid - 1.0, 2.0 * (y + 0.5) / grid - 1.0));
      image.push_back(s.hit ? luminance(s.B) : NAN);
    }
  return image;
}

}  // namespace walkrad
