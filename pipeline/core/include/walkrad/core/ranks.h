// The ranks of a bake run under mpirun (issue 28): Open MPI's MPI_COMM_WORLD, or one rank without it.
// Without mpirun MPI is never started, and everything runs as one process does.
//
// What is divided so far: the evaluation of each refinement round's new links (link_evaluation.cpp)
// and of the output vertices' radiosity (surface_mesher.cpp), by contiguous blocks of about equal cost
// in their own order, each rank's results gathered by every rank (MPI_Allgatherv). Each result depends
// only on its own inputs (a link's random numbers are seeded by its two nodes, a vertex's by its
// position), so the bake does not depend on the number of ranks. With Jacobi sweeps the solve's links
// are divided as well (walkrad/hierarchical/link_owners.h). Everything else (the scene, the nodes) is
// replicated; rank 0 alone writes the bake (docs/scaling.md).
#pragma once

#include <chrono>
#include <cstdint>
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
template <class T>
void share_blocks(std::vector<T>& v, const std::vector<size_t>& blocks) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (blocks.back() != v.size()) throw std::runtime_error("share_blocks: the blocks do not cover the list");
  all_gather_blocks(v.data(), sizeof(T), blocks);
}

}  // namespace walkrad
