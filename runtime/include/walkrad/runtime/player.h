// Player: the runtime's public face. Opens a bake folder (manifest.json + chunk files), streams its
// chunks ahead of the camera under a memory budget (chunk_cache.h, chunk_priority.h) and draws the
// resident ones into the bound framebuffer (a window's or a headless Framebuffer), measuring as it
// goes. Everything it does needs a current OpenGL 3.3 core context on the calling thread (the
// render thread: HeadlessContext or WindowContext); chunk files are read on worker threads.
//
//   Player player = Player::open(dir, settings);
//   each frame: player.update(camera); player.draw(width, height, wait);
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "walkrad/formats/manifest.h"
#include "walkrad/runtime/chunk_cache.h"
#include "walkrad/runtime/chunk_priority.h"
#include "walkrad/runtime/render_stats.h"
#include "walkrad/runtime/renderer.h"

namespace walkrad {

// What a frame does about needed chunks (chunks_needed) that are not resident.
enum class MissPolicy {
  kDrawWithout,  // interactive: never wait; the chunk appears a frame or two later
  kWait,         // headless: wait for them, so every frame is complete
};

class Player {
 public:
  // Reads BAKE_DIR/manifest.json and starts the loader's workers; chunks come with update(). Throws
  // InputError naming the faulty file, GraphicsError when the shaders cannot be built.
  static Player open(const std::string& bake_dir, const StreamSettings& settings = {});

  const Manifest& manifest() const { return manifest_; }
  // The stats so far, the cache's counters read now.
  const RenderStats& stats();
  const ChunkCache& cache() const { return *chunks_; }

  // Where the camera is: uploads what the workers have decoded, evicts, asks for what comes next.
  void update(const CameraPlace& camera);
  // Draws one frame of width × height pixels from the camera of the last update (the projection
  // uses this aspect and the viewpoint's vertical field of view). A needed chunk that is not
  // resident counts as a miss, except on the first frame (that wait, which also covers what the next
  // path frame needs, is the time to first frame).
  void draw(int width, int height, MissPolicy policy);
  // update + draw(kWait) for a viewpoint off any path: the chunks in its frustum are drawn.
  void draw(const Viewpoint& view, int width, int height);

 private:
  using Clock = std::chrono::steady_clock;
  Player(Manifest manifest, const std::string& bake_dir, const StreamSettings& settings, Clock::time_point opened);

  Manifest manifest_;
  StreamSettings settings_;
  std::unique_ptr<ChunkCache> chunks_;  // a pointer so that Player can move while workers refer to the cache
  Renderer renderer_;
  RenderStats stats_;
  Clock::time_point opened_;
  CameraPlace camera_;
  std::vector<double> priority_;  // of camera_
  double update_ms_ = 0;          // the CPU time of the last update, added to its frame's
};

}  // namespace walkrad
