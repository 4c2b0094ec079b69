// What fresh memory costs on this machine: the solve's node-sized arrays are freed and taken again
// round after round (glibc maps a block over 32 MiB afresh and unmaps it when freed), and each 4 KiB
// page is a fault at its first write: the cost that core/huge_pages.h avoids.
//
//   build/bench/walkrad_page_fault_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//
// Each iteration writes a 256 MiB block: mapped afresh (4 KiB pages), mapped afresh with
// madvise(MADV_HUGEPAGE) (transparent huge pages where the kernel allows them), or written again once
// resident (the cost of the writes alone).
#include <sys/mman.h>

#include <cstring>
#include <stdexcept>

#include <benchmark/benchmark.h>

namespace {

constexpr size_t kBytes = size_t(256) << 20;

void* map_block() {
  void* p = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::runtime_error("mmap failed");
  return p;
}

void BM_FreshPages(benchmark::State& state) {
  for (auto _ : state) {
    void* p = map_block();
    std::memset(p, 0, kBytes);
    benchmark::DoNotOptimize(p);
    munmap(p, kBytes);
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(kBytes));
}

void BM_FreshHugePages(benchmark::State& state) {
  for (auto _ : state) {
    void* p = map_block();
    madvise(p, kBytes, MADV_HUGEPAGE);
    std::memset(p, 0, kBytes);
    benchmark::DoNotOptimize(p);
    munmap(p, kBytes);
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(kBytes));
}

void BM_ResidentPages(benchmark::State& state) {
  void* p = map_block();
  std::memset(p, 1, kBytes);
  for (auto _ : state) {
    std::memset(p, 0, kBytes);
    benchmark::DoNotOptimize(p);
    benchmark::ClobberMemory();
  }
  munmap(p, kBytes);
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(kBytes));
}

}  // namespace

BENCHMARK(BM_FreshPages)->Unit(benchmark::kMillisecond)->Iterations(4);
BENCHMARK(BM_FreshHugePages)->Unit(benchmark::kMillisecond)->Iterations(4);
BENCHMARK(BM_ResidentPages)->Unit(benchmark::kMillisecond)->Iterations(4);

BENCHMARK_MAIN();
