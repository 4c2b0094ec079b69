// Player: the runtime's public face. Opens a bake folder (manifest.json + chunk-NNNN.glb), keeps
// its chunks on the GPU and draws the bake from any viewpoint into the bound framebuffer (a
// window's or a headless Framebuffer), measuring as it goes. Everything it does needs a current
// OpenGL 3.3 core context on the calling thread (HeadlessContext or WindowContext).
#pragma once

#include <chrono>
#include <string>

#include "walkrad/formats/manifest.h"
#include "walkrad/runtime/chunk_cache.h"
#include "walkrad/runtime/render_stats.h"
#include "walkrad/runtime/renderer.h"

namespace walkrad {

class Player {
 public:
  // Reads BAKE_DIR/manifest.json and loads every chunk. Throws InputError naming the faulty file,
  // GraphicsError when the shaders cannot be built.
  static Player open(const std::string& bake_dir);

  const Manifest& manifest() const { return manifest_; }
  const RenderStats& stats() const { return stats_; }

  // Draws one frame of width × height pixels (the projection uses this aspect and the viewpoint's
  // vertical field of view).
  void draw(const Viewpoint& view, int width, int height);

 private:
  using Clock = std::chrono::steady_clock;
  Player(Manifest manifest, const std::string& bake_dir, Clock::time_point opened);

  Manifest manifest_;
  ChunkCache chunks_;
  Renderer renderer_;
  RenderStats stats_;
  Clock::time_point opened_;
};

}  // namespace walkrad
