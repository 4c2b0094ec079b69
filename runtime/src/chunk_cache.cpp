// ChunkCache (chunk_cache.h): chunk files → ChunkMesh (formats' reader, Draco decoded there) →
// GpuMesh. The CPU copy is dropped once uploaded: the runtime keeps no second copy of a bake.
#include "walkrad/runtime/chunk_cache.h"

#include <filesystem>
#include <system_error>

#include "walkrad/formats/chunk.h"
#include "walkrad/formats/error.h"

namespace walkrad {

ChunkCache::ChunkCache(std::string bake_dir, const Manifest& manifest) {
  // The manifest reader has already refused chunk names that would leave the bake folder.
  for (const ChunkInfo& chunk : manifest.chunks)
    files_.push_back((std::filesystem::path(bake_dir) / chunk.file).string());
}

void ChunkCache::load_all() {
  resident_.clear();
  bytes_loaded_ = 0;
  resident_.reserve(files_.size());
  for (const std::string& file : files_) {
    resident_.emplace_back(read_chunk(file));
    std::error_code error;
    const uintmax_t size = std::filesystem::file_size(file, error);
    if (error) throw InputError(file, "", "cannot read its size: " + error.message());
    bytes_loaded_ += size;
  }
}

}  // namespace walkrad
