// Player (player.h): manifest → chunk cache → renderer, with the timings of RenderStats.
#include "walkrad/runtime/player.h"

#include <filesystem>

#include <epoxy/gl.h>

#include "walkrad/runtime/camera.h"

namespace walkrad {

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Player Player::open(const std::string& bake_dir) {
  const Clock::time_point opened = Clock::now();
  return Player(read_manifest((std::filesystem::path(bake_dir) / "manifest.json").string()), bake_dir, opened);
}

Player::Player(Manifest manifest, const std::string& bake_dir, Clock::time_point opened)
    : manifest_(std::move(manifest)), chunks_(bake_dir, manifest_), opened_(opened) {
  chunks_.load_all();
  stats_.open_ms = ms_since(opened_);
  stats_.bytes_loaded = chunks_.bytes_loaded();
  stats_.chunks_resident = chunks_.resident().size();
  stats_.chunks_total = chunks_.chunk_count();
}

void Player::draw(const Viewpoint& view, int width, int height) {
  const Clock::time_point start = Clock::now();
  const Mat4 view_projection = walkrad::view_projection(view, manifest_.bounds, double(width) / double(height));
  renderer_.begin_frame(width, height);
  for (const GpuMesh& mesh : chunks_.resident()) renderer_.draw(mesh, view_projection);
  stats_.frame_cpu_ms.push_back(ms_since(start));
  if (stats_.frame_cpu_ms.size() == 1) {
    // Only the first frame waits for the GPU: "first frame" means on screen, not merely submitted.
    glFinish();
    stats_.time_to_first_frame_ms = ms_since(opened_);
  }
}

}  // namespace walkrad
