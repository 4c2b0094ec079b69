// Chunk priority (chunk_priority.h): importance of the viewpoints ahead, then distance.
#include "walkrad/runtime/chunk_priority.h"

#include <algorithm>
#include <cmath>

#include "walkrad/runtime/camera.h"

namespace walkrad {

namespace {

// Orders the chunks that no viewpoint ahead sees without outranking one that it does: those are
// worth at least 1/(L + 1), above 1e-7 for any lookahead under 9,000,000 frames.
constexpr double kDistanceWeight = 1e-7;
// Off the path, chunks behind the camera still come, after those in front of it.
constexpr double kOutsideFrustumWeight = 0.25;

// A chunk's importance at a frame, widened to the frames just before and after: the bake samples each
// viewpoint with a finite grid of rays, which can miss a sliver of a chunk (seen through a doorway at a
// grazing angle) that the rasteriser still draws; the neighbouring frames almost always catch it.
double importance_at(const ChunkInfo& chunk, size_t frame) {
  double most = 0.0;
  for (size_t f = frame == 0 ? 0 : frame - 1; f <= frame + 1; ++f)
    if (f < chunk.importance.size()) most = std::max(most, double(chunk.importance[f]));
  return most;
}

}  // namespace

double distance_to_bounds(const Vec3& p, const Bounds& b) {
  if (b.empty()) return INFINITY;
  const Vec3 d{std::fmax(std::fmax(b.lo.x - p.x, 0.0), p.x - b.hi.x),
               std::fmax(std::fmax(b.lo.y - p.y, 0.0), p.y - b.hi.y),
               std::fmax(std::fmax(b.lo.z - p.z, 0.0), p.z - b.hi.z)};
  return length(d);
}

bool bounds_in_frustum(const Viewpoint& view, const Bounds& scene_bounds, const Bounds& box) {
  if (box.empty()) return false;
  const Mat4 m = view_projection(view, scene_bounds, view.aspect);
  // Clip space: inside is −w ≤ x, y, z ≤ w. Outside when all 8 corners fail the same inequality.
  int outside[6] = {0, 0, 0, 0, 0, 0};
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p{corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y, corner & 4 ? box.hi.z : box.lo.z};
    const std::array<float, 4> c = m.transform(float(p.x), float(p.y), float(p.z), 1.0f);
    for (int axis = 0; axis < 3; ++axis) {
      if (c[size_t(axis)] < -c[3]) ++outside[2 * axis];
      if (c[size_t(axis)] > c[3]) ++outside[2 * axis + 1];
    }
  }
  return std::none_of(std::begin(outside), std::end(outside), [](int n) { return n == 8; });
}

std::vector<double> chunk_priorities(const Manifest& manifest, const CameraPlace& camera, size_t lookahead) {
  const size_t frames = manifest.viewpoints.size();
  std::vector<double> priority(manifest.chunks.size(), 0.0);
  for (size_t c = 0; c < manifest.chunks.size(); ++c) {
    const ChunkInfo& chunk = manifest.chunks[c];
    const double near = 1.0 / (1.0 + distance_to_bounds(camera.view.position, chunk.bounds));
    if (!camera.path_frame || *camera.path_frame >= frames) {
      const bool seen = bounds_in_frustum(camera.view, manifest.bounds, chunk.bounds);
      priority[c] = (seen ? 1.0 : kOutsideFrustumWeight) * near;
      continue;
    }
    double ahead = 0.0;
    for (size_t k = 0; k <= lookahead; ++k) {
      size_t frame = *camera.path_frame + k;
      if (frame >= frames) {
        if (!camera.loop) break;
        frame %= frames;
      }
      const double importance = importance_at(chunk, frame);
      if (importance > 0.0) {  // the first frame ahead that needs it
        ahead = (double(lookahead + 1 - k) + 0.5 * std::min(importance, 1.0)) / double(lookahead + 1);
        break;
      }
    }
    priority[c] = ahead + kDistanceWeight * near;
  }
  return priority;
}

std::vector<uint32_t> chunks_needed(const Manifest& manifest, const CameraPlace& camera) {
  std::vector<uint32_t> needed;
  const bool on_path = camera.path_frame && *camera.path_frame < manifest.viewpoints.size();
  for (size_t c = 0; c < manifest.chunks.size(); ++c) {
    const ChunkInfo& chunk = manifest.chunks[c];
    if (on_path ? importance_at(chunk, *camera.path_frame) > 0.0
                : bounds_in_frustum(camera.view, manifest.bounds, chunk.bounds))
      needed.push_back(uint32_t(c));
  }
  return needed;
}

}  // namespace walkrad
