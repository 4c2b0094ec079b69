// ChunkLoader (chunk_loader.h): a mutex-guarded queue drained by a fixed set of std::threads.
#include "walkrad/runtime/chunk_loader.h"

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

LoadedChunk load(uint32_t chunk, const std::string& file) {
  LoadedChunk out;
  out.chunk = chunk;
  out.decoded_on = std::this_thread::get_id();
  try {
    out.mesh = read_chunk(file);
    // Display needs neither normals nor physical radiosity: free them before the mesh is counted.
    out.mesh.normals = {};
    out.mesh.radiosity = {};
    out.mesh.positions.shrink_to_fit();
    out.mesh.colors.shrink_to_fit();
    out.mesh.indices.shrink_to_fit();
    std::error_code error;
    out.file_bytes = std::filesystem::file_size(file, error);
    if (error) throw InputError(file, "", "cannot read its size: " + error.message());
  } catch (...) {
    out.mesh = {};
    out.error = std::current_exception();
  }
  return out;
}

}  // namespace

uint64_t display_bytes(const ChunkMesh& mesh) {
  return uint64_t(mesh.positions.size() + mesh.colors.size()) * sizeof(float) +
         uint64_t(mesh.indices.size()) * sizeof(uint32_t);
}

ChunkLoader::ChunkLoader(int threads) {
  if (threads < 1) throw std::invalid_argument("ChunkLoader: at least one worker thread");
  for (int i = 0; i < threads; ++i) workers_.emplace_back([this] { work(); });
}

ChunkLoader::~ChunkLoader() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  work_ready_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void ChunkLoader::request(uint32_t chunk, std::string file) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back({chunk, std::move(file)});
    ++pending_;
  }
  work_ready_.notify_one();
}

std::vector<LoadedChunk> ChunkLoader::take_finished() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<LoadedChunk> out = std::move(finished_);
  finished_.clear();
  pending_ -= out.size();
  return out;
}

std::vector<LoadedChunk> ChunkLoader::wait_finished() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (pending_ == 0) throw std::logic_error("ChunkLoader::wait_finished with nothing requested");
  work_done_.wait(lock, [this] { return !finished_.empty(); });
  std::vector<LoadedChunk> out = std::move(finished_);
  finished_.clear();
  pending_ -= out.size();
  return out;
}

std::set<std::thread::id> ChunkLoader::decode_threads() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return decode_threads_;
}

void ChunkLoader::work() {
  for (;;) {
    Request request;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      work_ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      request = std::move(queue_.front());
      queue_.pop_front();
    }
    LoadedChunk loaded = load(request.chunk, request.file);  // the slow part, outside the lock
    {
      std::lock_guard<std::mutex> lock(mutex_);
      decode_threads_.insert(loaded.decoded_on);
      finished_.push_back(std::move(loaded));
    }
    work_done_.notify_all();
  }
}

}  // namespace walkrad
