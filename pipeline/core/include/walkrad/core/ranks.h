// The ranks of a bake run under mpirun (issue 28): Open MPI's MPI_COMM_WORLD, or one rank without it.
// Without mpirun MPI is never started, and everything runs as one process does.
//
// What is divided so far: the evaluation of each refinement round's new links (link_evaluation.cpp),
// by contiguous blocks of about equal cost in the round's own order, each rank's results gathered by
// every rank (MPI_Allgatherv). Each link's evaluation depends only on its two nodes (its random numbers
// are seeded by them), so the bake does not depend on the number of ranks. Everything else (the scene,
// the refinement, the sweeps, the meshing) is replicated; rank 0 alone writes the bake.
#pragma once

#include <cstdint>
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

// Bytes this process has sent and received through all_gather (report.json).
uint64_t ranks_bytes_exchanged();

}  // namespace walkrad
