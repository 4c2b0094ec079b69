// The ranks of a bake run under mpirun: Open MPI's MPI_COMM_WORLD, or one rank without it.
// Without mpirun MPI is never started, and everything runs as one process does.
//
// What is divided: the evaluation of each refinement round's new links (link_evaluation.cpp)
// and of the output vertices' radiosity (surface_mesher.cpp), by contiguous blocks of about equal cost
// in their own order, each rank's results gathered by every rank (MPI_Allgatherv). Each result depends
// only on its own inputs (a link's random numbers are seeded by its two nodes, a vertex's by its
// position), so the bake does not depend on the number of ranks. With Jacobi sweeps the links are
// divided as well, to the end of the bake (walkrad/hierarchical/link_owners.h): what reads them runs on
// the rank holding them and shares what it found (share_owned). Everything else (the scene, the nodes)
// is replicated; rank 0 alone writes the bake (docs/scaling.md).
#pragma once

#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace walkrad {

struct Ranks {
  int rank = 0, size = 1;
};

// Starts MPI when the process was launched by mpirun (Open MPI's OMPI_COMM_WORLD_SIZE is set), else
// leaves it alone. Call once, first thing in main.
Ranks start_ranks(int* argc, char*** argv);
// Ends MPI if it was started (after every rank's last collective call).
void stop_ranks();
// Ends every rank at once, with this exit code (an error on one rank must not leave the others
// waiting in a collective call).
[[noreturn]] void abort_ranks(int code);
const Ranks& ranks();

// Every rank's bytes, in rank order, to every rank (MPI_Allgatherv); with one rank, `mine` itself.
std::vector<uint8_t> all_gather(const std::vector<uint8_t>& mine);

// Every rank's integers summed, element by element, into every rank's (MPI_Allreduce): integer sums
// do not depend on the order the ranks are added in. With one rank nothing happens.
void all_sum(int64_t* data, size_t count);
// The same for doubles, for what only reports a total (the energy audit): a sum of several ranks'
// parts rounds differently from one process's sum.
void all_sum(double* data, size_t count);

// Rank 0's bytes to every rank (MPI_Bcast): rank 0 reads a file that the other hosts need not have.
// With one rank, nothing happens.
void broadcast(std::vector<uint8_t>& bytes);
// The same for bytes whose count every rank knows.
void broadcast(uint8_t* data, size_t size);

// The first rank whose text differs from rank 0's (its text in *theirs), or -1 when every rank's is
// the same, e.g. build_identity(): ranks built from different sources would not bake alike.
int first_different_rank(const std::string& mine, std::string* theirs);

// Bytes this process has sent and received through all_gather and broadcast (report.json).
uint64_t ranks_bytes_exchanged();

// What one rank did of the divided work (report.json "ranks"): the items in its blocks (links, faces,
// vertices), the seconds it spent on them and in the exchanges (waiting for the others included), the
// bytes it sent, and its peak memory.
struct RankWork {
  uint64_t items = 0, bytes_sent = 0;
  uint64_t links = 0, rays = 0;  // of the items, the links it evaluated and their visibility rays
  uint64_t peak_memory_mb = 0;   // its peak resident memory (set by all_rank_work)
  // A divided solve (link_owners.h): the links it held at the end of the solve, and the most bytes its
  // links and its list of new links took at once (measured between the steps of each round).
  uint64_t links_held = 0, link_bytes_peak = 0;
  double compute_seconds = 0, exchange_seconds = 0;
};
RankWork& rank_work();  // this rank's, added to by the divided stages
// Every rank's, in rank order (a collective call: every rank makes it at the same point).
std::vector<RankWork> all_rank_work();

// [0, n) cut into one contiguous block per rank, in order, of about equal total cost (cost(k) > 0 for
// item k): the block boundaries, ranks().size + 1 of them. Every rank computes the same ones.
std::vector<size_t> rank_blocks(size_t n, const std::function<double(size_t)>& cost);

// Runs body(begin, end) on this rank's block of [0, n) (rank_blocks by cost), adds its items and its
// seconds to rank_work(), and returns the blocks, for share_blocks. With one rank: body(0, n).
template <class Body>
std::vector<size_t> run_my_block(size_t n, const std::function<double(size_t)>& cost, Body&& body) {
  const std::vector<size_t> blocks = rank_blocks(n, cost);
  const size_t begin = blocks[size_t(ranks().rank)], end = blocks[size_t(ranks().rank) + 1];
  const auto start = std::chrono::steady_clock::now();
  body(begin, end);
  rank_work().items += end - begin;
  rank_work().compute_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return blocks;
}

// Items [blocks[r], blocks[r + 1]) of `data` (items of `size` bytes) from rank r to every rank, in
// place (MPI_IN_PLACE: no second copy of the list). With one rank nothing happens.
void all_gather_blocks(void* data, size_t size, const std::vector<size_t>& blocks);

// v[blocks[r], blocks[r + 1]) from rank r to every rank (this rank's block is already in v). T is
// trivially copyable; with one rank nothing happens.
template <class T, class Allocator>
void share_blocks(std::vector<T, Allocator>& v, const std::vector<size_t>& blocks) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (blocks.back() != v.size()) throw std::runtime_error("share_blocks: the blocks do not cover the list");
  all_gather_blocks(v.data(), sizeof(T), blocks);
}

namespace ranks_detail {

// share_owned's exchange, by bytes: item i's size(i) bytes, written by put(i, to) on its owner and read
// by take(i, from) on the others (every rank knows every item's owner and size).
template <class Owner, class Size, class Put, class Take>
void share_owned_bytes(size_t n, Owner owner, Size size, Put put, Take take) {
  const Ranks& r = ranks();
  std::vector<uint8_t> mine;
  std::vector<size_t> offset(size_t(r.size) + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    const int o = owner(i);
    if (o < 0) continue;
    const size_t bytes = size(i);
    offset[size_t(o) + 1] += bytes;
    if (o != r.rank || bytes == 0) continue;
    mine.resize(mine.size() + bytes);
    put(i, mine.data() + mine.size() - bytes);
  }
  const std::vector<uint8_t> all = all_gather(mine);
  std::vector<uint8_t>().swap(mine);
  for (size_t k = 1; k < offset.size(); ++k) offset[k] += offset[k - 1];
  for (size_t i = 0; i < n; ++i) {
    const int o = owner(i);
    if (o < 0) continue;
    size_t& at = offset[size_t(o)];
    const size_t bytes = size(i);
    if (o != r.rank && bytes) take(i, all.data() + at);
    at += bytes;
  }
}

}  // namespace ranks_detail

// Items [0, n) each computed on one rank, owner(i) (an int; negative: an item no rank sends), given
// to every other rank: each rank packs get(i) of its own items in index order, every rank receives
// every pack (all_gather) and calls set(i, value) for the others' items. Every rank must know every
// item's owner. A collective call; with one rank nothing happens.
template <class T, class Owner, class Get, class Set>
void share_owned(size_t n, Owner owner, Get get, Set set) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (ranks().size == 1) return;
  ranks_detail::share_owned_bytes(
      n, owner, [](size_t) { return sizeof(T); },
      [&](size_t i, uint8_t* to) {
        const T v = get(i);
        std::memcpy(to, &v, sizeof(T));
      },
      [&](size_t i, const uint8_t* from) {
        T v;
        std::memcpy(&v, from, sizeof(T));
        set(i, v);
      });
}

// The same for a value per item kept in a vector.
template <class T, class Allocator, class Owner>
void share_owned(std::vector<T, Allocator>& v, Owner owner) {
  share_owned<T>(v.size(), owner, [&](size_t i) { return v[i]; }, [&](size_t i, const T& x) { v[i] = x; });
}

// The same for a list per item (each rank sends its items' counts, then their elements; T's bytes
// are copied, so T holds no pointers).
template <class T, class Owner>
void share_owned_lists(std::vector<std::vector<T>>& lists, Owner owner) {
  static_assert(std::is_trivially_copy_constructible_v<T> && std::is_trivially_destructible_v<T>);
  if (ranks().size == 1) return;
  share_owned<uint32_t>(lists.size(), owner, [&](size_t i) { return uint32_t(lists[i].size()); },
                        [&](size_t i, uint32_t count) { lists[i].resize(count); });
  ranks_detail::share_owned_bytes(
      lists.size(), owner, [&](size_t i) { return lists[i].size() * sizeof(T); },
      [&](size_t i, uint8_t* to) { std::memcpy(to, static_cast<const void*>(lists[i].data()), lists[i].size() * sizeof(T)); },
      [&](size_t i, const uint8_t* from) { std::memcpy(static_cast<void*>(lists[i].data()), from, lists[i].size() * sizeof(T)); });
}

}  // namespace walkrad
