#include "walkrad/accuracy/reference_set.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <stb_image_write.h>

#include "walkrad/formats/error.h"
#include "walkrad/visibility/exposure.h"

namespace walkrad {

ReferenceSet trace_reference(const Scene& scene, const RayScene& rays, const ReferenceTracer& tracer,
                             std::vector<ViewRay> view_rays, int samples, uint64_t seed) {
  const auto t0 = std::chrono::steady_clock::now();
  ReferenceSet r;
  r.rays = std::move(view_rays);
  const size_t n = r.rays.size();
  r.distance.assign(n, NAN);
  r.luminance.assign(n, NAN);
  r.standard_error.assign(n, NAN);
  r.B.assign(n, Vec3{});
  std::vector<SurfacePoint> points;
  std::vector<size_t> index;
  for (size_t k = 0; k < n; ++k) {
    r.weight.push_back(r.rays[k].weight);
    const RayScene::Hit hit = rays.intersect(r.rays[k].origin, r.rays[k].direction);
    ++r.rays_cast;
    if (!hit.hit || dot(polygon_normal(scene.polygons[hit.polygon]), r.rays[k].direction) >= 0) continue;
    r.distance[k] = length(hit.position - r.rays[k].origin);
    const Material& m = scene.materials[scene.polygons[hit.polygon].material];
    if (m.emits()) {
      r.B[k] = m.emission;
      continue;
    }
    points.push_back({hit.polygon, hit.position});
    index.push_back(k);
  }
  ReferenceSettings rs;
  rs.samples = samples;
  rs.seed = seed;
  const std::vector<RadiosityEstimate> est = tracer.estimate(points, rs, r.rays_cast);
  for (size_t i = 0; i < est.size(); ++i) {
    r.B[index[i]] = est[i].B;
    r.luminance[index[i]] = luminance(est[i].B);
    r.standard_error[index[i]] = est[i].luminance_error;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::vector<double> sample_bake(const BakeSampler& bake, const ReferenceSet& ref, double tolerance) {
  std::vector<double> out(ref.rays.size(), NAN);
  for (size_t k = 0; k < ref.rays.size(); ++k) {
    if (std::isnan(ref.luminance[k])) continue;
    const BakeSampler::Sample s = bake.along(ref.rays[k].origin, ref.rays[k].direction);
    if (s.hit && std::fabs(s.distance - ref.distance[k]) <= tolerance) out[k] = luminance(s.B);
  }
  return out;
}

void write_image_png(const std::string& path, const std::vector<Vec3>& B, const std::vector<double>& lum, int width,
                     int height) {
  std::vector<double> seen;
  for (double l : lum)
    if (!std::isnan(l)) seen.push_back(l / kPi);
  const double exposure = exposure_for(seen);
  std::vector<uint8_t> rgb(size_t(width) * size_t(height) * 3);
  for (size_t k = 0; k < B.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const double v = std::clamp(B[k][c] / kPi * exposure, 0.0, 1.0);
      const double s = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
      rgb[3 * k + size_t(c)] = uint8_t(std::lround(255 * s));
    }
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3)) throw OutputError(path + ": cannot write PNG");
}

}  // namespace walkrad
