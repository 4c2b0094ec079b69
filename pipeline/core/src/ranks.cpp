#include "walkrad/core/ranks.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <mpi.h>
#include <sys/resource.h>

namespace walkrad {

namespace {

Ranks g_ranks;
bool g_started = false;
uint64_t g_bytes = 0;
RankWork g_work;

}  // namespace

Ranks start_ranks(int* argc, char*** argv) {
  const char* world = std::getenv("OMPI_COMM_WORLD_SIZE");
  if (!world || std::atoi(world) < 1 || g_started) return g_ranks;
  int provided = 0;
  // Threads (TBB) run inside each rank, but only the main thread calls MPI.
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  g_started = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_ranks.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_ranks.size);
  return g_ranks;
}

void stop_ranks() {
  if (!g_started) return;
  MPI_Finalize();
  g_started = false;
}

void abort_ranks(int code) {
  if (g_started && g_ranks.size > 1) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

const Ranks& ranks() { return g_ranks; }

std::vector<uint8_t> all_gather(const std::vector<uint8_t>& mine) {
  if (!g_started || g_ranks.size == 1) return mine;
  if (mine.size() > size_t(INT32_MAX)) throw std::runtime_error("all_gather: more than 2 GB from one rank");
  const int count = int(mine.size());
  std::vector<int> counts(size_t(g_ranks.size)), offsets(size_t(g_ranks.size));
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  int64_t total = 0;
  for (size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = int(total);
    total += counts[r];
  }
  if (total > int64_t(INT32_MAX)) throw std::runtime_error("all_gather: more than 2 GB in all");
  std::vector<uint8_t> all(static_cast<size_t>(total));
  const auto start = std::chrono::steady_clock::now();
  MPI_Allgatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, MPI_COMM_WORLD);
  g_work.exchange_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  g_work.bytes_sent += uint64_t(count);
  g_bytes += uint64_t(count) + uint64_t(total - count);
  return all;
}

namespace {

// MPI_Allreduce of a sum in place, in pieces (MPI counts are ints).
void all_sum_as(void* data, size_t count, size_t size, MPI_Datatype type) {
  if (!g_started || g_ranks.size == 1) return;
  const auto start = std::chrono::steady_clock::now();
  constexpr size_t kPiece = size_t(1) << 27;
  for (size_t at = 0; at < count; at += kPiece)
    MPI_Allreduce(MPI_IN_PLACE, static_cast<uint8_t*>(data) + at * size, int(std::min(kPiece, count - at)), type, MPI_SUM,
                  MPI_COMM_WORLD);
  g_work.exchange_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  g_work.bytes_sent += uint64_t(count * size);
  g_bytes += uint64_t(count * size) * 2;  // its own sent, the sum received
}

}  // namespace

void all_sum(int64_t* data, size_t count) { all_sum_as(data, count, sizeof(int64_t), MPI_INT64_T); }
void all_sum(double* data, size_t count) { all_sum_as(data, count, sizeof(double), MPI_DOUBLE); }

void broadcast(std::vector<uint8_t>& bytes) {
  if (!g_started || g_ranks.size == 1) return;
  uint64_t size = bytes.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  bytes.resize(size_t(size));
  broadcast(bytes.data(), bytes.size());
}

void broadcast(uint8_t* data, size_t size) {
  if (!g_started || g_ranks.size == 1) return;
  const auto start = std::chrono::steady_clock::now();
  constexpr size_t kPiece = size_t(1) << 30;  // MPI counts are ints
  for (size_t at = 0; at < size; at += kPiece)
    MPI_Bcast(data + at, int(std::min(kPiece, size - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
  g_work.exchange_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (g_ranks.rank == 0) g_work.bytes_sent += uint64_t(size) * uint64_t(g_ranks.size - 1);
  g_bytes += uint64_t(size) * (g_ranks.rank == 0 ? uint64_t(g_ranks.size - 1) : 1);
}

int first_different_rank(const std::string& mine, std::string* theirs) {
  std::vector<uint8_t> text(mine.begin(), mine.end());
  text.push_back(0);  // each rank's text ends with a 0: the gathered texts split there
  const std::vector<uint8_t> all = all_gather(text);
  std::vector<std::string> texts(1);
  for (uint8_t c : all) {
    if (c) texts.back().push_back(char(c));
    else texts.emplace_back();
  }
  texts.pop_back();
  for (size_t r = 1; r < texts.size(); ++r)
    if (texts[r] != texts[0]) {
      if (theirs) *theirs = texts[r];
      return int(r);
    }
  return -1;
}

void all_gather_blocks(void* data, size_t size, const std::vector<size_t>& blocks) {
  if (!g_started || g_ranks.size == 1) return;
  std::vector<int> counts(size_t(g_ranks.size)), offsets(size_t(g_ranks.size));
  for (size_t r = 0; r < counts.size(); ++r) {
    if (blocks[r + 1] > size_t(INT32_MAX)) throw std::runtime_error("all_gather_blocks: more than 2^31 items");
    counts[r] = int(blocks[r + 1] - blocks[r]);
    offsets[r] = int(blocks[r]);
  }
  MPI_Datatype item;  // counts in items, not bytes: lists of more than 2 GB
  MPI_Type_contiguous(int(size), MPI_BYTE, &item);
  MPI_Type_commit(&item);
  const auto start = std::chrono::steady_clock::now();
  MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, data, counts.data(), offsets.data(), item, MPI_COMM_WORLD);
  g_work.exchange_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  MPI_Type_free(&item);
  const uint64_t mine = uint64_t(counts[size_t(g_ranks.rank)]) * size;
  g_work.bytes_sent += mine;
  g_bytes += uint64_t(blocks.back()) * size;  // its own block sent, the others' received
}

uint64_t ranks_bytes_exchanged() { return g_bytes; }

RankWork& rank_work() { return g_work; }

std::vector<RankWork> all_rank_work() {
  rusage usage{};
  if (::getrusage(RUSAGE_SELF, &usage) == 0) g_work.peak_memory_mb = uint64_t(usage.ru_maxrss) / 1024;  // KiB on Linux
  std::vector<uint8_t> mine(sizeof(RankWork));
  std::memcpy(mine.data(), &g_work, sizeof(RankWork));
  const std::vector<uint8_t> all = all_gather(mine);
  std::vector<RankWork> out(all.size() / sizeof(RankWork));
  if (!out.empty()) std::memcpy(out.data(), all.data(), out.size() * sizeof(RankWork));
  return out;
}

std::vector<size_t> rank_blocks(size_t n, const std::function<double(size_t)>& cost) {
  const int size = g_ranks.size;
  std::vector<size_t> blocks(size_t(size) + 1, n);
  blocks[0] = 0;
  if (size == 1) return blocks;
  double total = 0;
  for (size_t k = 0; k < n; ++k) total += cost(k);
  double before = 0;
  int next = 1;  // the block whose start comes next
  for (size_t k = 0; k < n && next < size; ++k) {
    while (next < size && before >= total * next / size) blocks[size_t(next++)] = k;
    before += cost(k);
  }
  return blocks;
}

}  // namespace walkrad
