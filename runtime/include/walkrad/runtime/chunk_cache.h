// ChunkCache: which of a bake's chunks are on the GPU, and what it cost to bring them there. For
// now every chunk is loaded at once; streaming by importance along the path (docs/architecture.md,
// "runtime/ stream") will decide here what to load and evict, without touching the renderer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "walkrad/formats/manifest.h"
#include "walkrad/runtime/gpu_mesh.h"

namespace walkrad {

class ChunkCache {
 public:
  ChunkCache(std::string bake_dir, const Manifest& manifest);

  // Reads every chunk the manifest names and uploads it (needs a current GL context). Throws
  // InputError naming the chunk file when one is missing or invalid.
  void load_all();

  const std::vector<GpuMesh>& resident() const { return resident_; }
  size_t chunk_count() const { return files_.size(); }
  uint64_t bytes_loaded() const { return bytes_loaded_; }  // chunk file bytes read from disk

 private:
  std::vector<std::string> files_;  // paths of the manifest's chunks, in its order
  std::vector<GpuMesh> resident_;
  uint64_t bytes_loaded_ = 0;
};

}  // namespace walkrad
