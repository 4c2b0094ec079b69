// ChunkLoader: worker threads (std::thread, no TBB) that read chunk files and decode them
// (read_chunk: glTF parse, Draco decode) off the render thread, so a frame never waits on I/O.
// Requests are served first come, first served: the cache issues them in priority order and keeps
// only a few in flight, so a late, urgent chunk never waits behind a long queue.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "walkrad/formats/chunk.h"

namespace walkrad {

struct LoadedChunk {
  uint32_t chunk = 0;
  ChunkMesh mesh;               // positions, colours and indices only: normals and radiosity dropped
  uint64_t file_bytes = 0;      // bytes read from disk
  std::exception_ptr error;     // set instead of mesh when the file could not be read
  std::thread::id decoded_on;   // the thread that ran read_chunk
};

class ChunkLoader {
 public:
  explicit ChunkLoader(int threads);
  // Stops the workers; requests not started are dropped, those under way finish first.
  ~ChunkLoader();
  ChunkLoader(const ChunkLoader&) = delete;
  ChunkLoader& operator=(const ChunkLoader&) = delete;

  void request(uint32_t chunk, std::string file);
  // The chunks decoded since the last call, without waiting.
  std::vector<LoadedChunk> take_finished();
  // Waits until at least one request has finished (there must be one pending), then takes them all.
  std::vector<LoadedChunk> wait_finished();

  // Every thread that has run read_chunk so far (for the test that none is the render thread).
  std::set<std::thread::id> decode_threads() const;

 private:
  void work();

  struct Request {
    uint32_t chunk = 0;
    std::string file;
  };
  mutable std::mutex mutex_;
  std::condition_variable work_ready_, work_done_;
  std::deque<Request> queue_;
  std::vector<LoadedChunk> finished_;
  std::set<std::thread::id> decode_threads_;
  size_t pending_ = 0;  // requested and not yet taken
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

// Bytes a chunk's display data takes: positions and colours (3 floats each per vertex) and the
// triangle indices — what GpuMesh uploads and what a decoded mesh waiting for upload holds.
uint64_t display_bytes(const ChunkMesh& mesh);

}  // namespace walkrad
