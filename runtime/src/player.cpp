// Player (player.h): camera → priorities → chunk cache → renderer, with the timings of RenderStats.
#include "walkrad/runtime/player.h"

#include <algorithm>
#include <filesystem>

#include <epoxy/gl.h>

#include "walkrad/runtime/camera.h"

namespace walkrad {

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Player Player::open(const std::string& bake_dir, const StreamSettings& settings) {
  const Clock::time_point opened = Clock::now();
  return Player(read_manifest((std::filesystem::path(bake_dir) / "manifest.json").string()), bake_dir, settings,
                opened);
}

Player::Player(Manifest manifest, const std::string& bake_dir, const StreamSettings& settings,
               Clock::time_point opened)
    : manifest_(std::move(manifest)),
      settings_(settings),
      chunks_(std::make_unique<ChunkCache>(bake_dir, manifest_, settings)),
      opened_(opened) {
  stats_.open_ms = ms_since(opened_);
  stats_.chunks_total = chunks_->chunk_count();
  stats_.budget_bytes = chunks_->budget_bytes();
}

const RenderStats& Player::stats() {
  stats_.bytes_loaded = chunks_->bytes_loaded();
  stats_.chunk_loads = chunks_->loads();
  stats_.chunk_evictions = chunks_->evictions();
  stats_.chunks_resident = chunks_->resident_count();
  stats_.resident_bytes = chunks_->resident_bytes();
  stats_.max_resident_bytes = chunks_->max_resident_bytes();
  return stats_;
}

void Player::update(const CameraPlace& camera) {
  const Clock::time_point start = Clock::now();
  camera_ = camera;
  priority_ = chunk_priorities(manifest_, camera_, settings_.lookahead_frames);
  chunks_->update(priority_);
  update_ms_ = ms_since(start);
}

void Player::draw(int width, int height, MissPolicy policy) {
  const Clock::time_point start = Clock::now();
  const bool first = stats_.frame_cpu_ms.empty();
  const std::vector<uint32_t> needed = chunks_needed(manifest_, camera_);
  uint64_t missing = 0;
  for (uint32_t c : needed) missing += chunks_->mesh(c) == nullptr;
  if (missing && !first) {
    stats_.chunk_misses += missing;
    ++stats_.frames_with_misses;
  }
  if (first && camera_.path_frame && *camera_.path_frame + 1 < manifest_.viewpoints.size()) {
    // The first frame is a loading screen anyway: it also waits for what the next frame needs, which
    // no prefetch could bring in the one frame's time between them.
    CameraPlace next = camera_;
    ++*next.path_frame;
    std::vector<uint32_t> soon = needed;
    for (uint32_t c : chunks_needed(manifest_, next))
      if (std::find(soon.begin(), soon.end(), c) == soon.end()) soon.push_back(c);
    chunks_->wait_for(soon, priority_);
  } else if (missing && (first || policy == MissPolicy::kWait)) {
    chunks_->wait_for(needed, priority_);
  }

  const Mat4 view_projection = walkrad::view_projection(camera_.view, manifest_.bounds, double(width) / double(height));
  renderer_.begin_frame(width, height);
  // In chunk order whatever arrived when, so that a frame is the same as with every chunk resident.
  for (uint32_t c = 0; c < chunks_->chunk_count(); ++c)
    if (const GpuMesh* mesh = chunks_->mesh(c)) renderer_.draw(*mesh, view_projection);
  stats_.frame_cpu_ms.push_back(update_ms_ + ms_since(start));
  update_ms_ = 0;
  if (first) {
    // Only the first frame waits for the GPU: "first frame" means on screen, not merely submitted.
    glFinish();
    stats_.time_to_first_frame_ms = ms_since(opened_);
  }
}

void Player::draw(const Viewpoint& view, int width, int height) {
  update(CameraPlace{view, std::nullopt, false});
  draw(width, height, MissPolicy::kWait);
}

}  // namespace walkrad
