// ChunkCache: which of a bake's chunks are resident, under a memory budget, and what it cost to
// bring them there. The render thread calls update() once per frame with the chunks' priorities
// (chunk_priority.h): it uploads what the workers (chunk_loader.h) decoded, evicts the least useful
// chunks when room is needed, and asks for the most useful missing ones. Only the GPU upload runs
// on the render thread; reading and decoding never do.
//
// Resident bytes (what the budget bounds): for each chunk on the GPU, its buffers (positions and
// colours, 12 bytes each per vertex, indices 4 bytes each); for each chunk asked for and not yet
// uploaded, a reservation of the same quantity — exact when the chunk was loaded before, else the
// bound 84 bytes per triangle (3 vertices per triangle at most, for meshes without unused
// vertices). A decoded mesh waiting for upload holds exactly its display bytes on the CPU (normals
// and radiosity are dropped on the worker), and is dropped once uploaded, so a chunk is never
// counted twice. Not counted: the decoder's working memory while a worker decodes (at most one
// whole chunk per worker), and the manifest.
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "walkrad/formats/manifest.h"
#include "walkrad/runtime/chunk_loader.h"
#include "walkrad/runtime/gpu_mesh.h"

namespace walkrad {

struct StreamSettings {
  uint64_t budget_bytes = 0;     // resident bytes allowed (see above); 0: no limit
  int worker_threads = 2;        // read and decode threads
  size_t lookahead_frames = 90;  // how far ahead on the path priority looks: 3 s at 30 frames/s
};

class ChunkCache {
 public:
  ChunkCache(std::string bake_dir, const Manifest& manifest, const StreamSettings& settings);
  ~ChunkCache();
  ChunkCache(const ChunkCache&) = delete;
  ChunkCache& operator=(const ChunkCache&) = delete;

  // Render thread, once per frame, with one priority per chunk (larger: more useful). Never waits
  // for a worker. Throws InputError naming the chunk file when a worker could not read one.
  void update(const std::vector<double>& priority);
  // Render thread: waits until the given chunks are resident, asking for those not yet asked for
  // and evicting chunks outside the list to make room. Returns how many of them did not fit in the
  // budget even so (they stay missing).
  size_t wait_for(const std::vector<uint32_t>& chunks, const std::vector<double>& priority);

  const GpuMesh* mesh(uint32_t chunk) const;  // null while the chunk is not resident
  size_t chunk_count() const { return slots_.size(); }
  size_t resident_count() const;
  uint64_t resident_bytes() const { return resident_bytes_; }
  uint64_t max_resident_bytes() const { return max_resident_bytes_; }  // since the cache was made
  uint64_t budget_bytes() const { return budget_; }                     // 0: no limit
  uint64_t bytes_loaded() const { return bytes_loaded_; }               // chunk file bytes read from disk
  uint64_t loads() const { return loads_; }
  uint64_t evictions() const { return evictions_; }
  // Threads that ran read_chunk (the workers'), for the test that the render thread never did.
  std::set<std::thread::id> decode_threads() const { return loader_.decode_threads(); }

 private:
  enum class State { kAbsent, kLoading, kResident };
  struct Slot {
    std::string file;
    uint64_t triangles = 0;
    State state = State::kAbsent;
    uint64_t bytes = 0;          // display bytes once known (the chunk was loaded before)
    bool bytes_known = false;
    uint64_t reserved = 0;       // counted in resident_bytes_ while loading
    std::optional<GpuMesh> gpu;
  };

  uint64_t estimate(const Slot& slot) const;
  uint64_t room() const;  // budget left
  void add_bytes(uint64_t bytes);
  void ask(uint32_t chunk);
  void evict(uint32_t chunk);
  // Evicts resident chunks not in `keep`, least useful first, until `bytes` fit. False if they cannot.
  bool make_room(uint64_t bytes, const std::vector<bool>& keep, const std::vector<double>& priority);
  void arrive(std::vector<LoadedChunk> loaded, const std::vector<double>& priority);

  std::vector<Slot> slots_;
  uint64_t budget_;
  size_t max_in_flight_;
  size_t in_flight_ = 0;
  uint64_t resident_bytes_ = 0, max_resident_bytes_ = 0, bytes_loaded_ = 0, loads_ = 0, evictions_ = 0;
  ChunkLoader loader_;  // last: its workers stop before the slots go
};

}  // namespace walkrad
