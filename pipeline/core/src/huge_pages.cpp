#include "walkrad/core/huge_pages.h"

#include <cstdint>

#include <tbb/parallel_for.h>

#if defined(__linux__)
#include <sys/mman.h>
#else
#include <cstdlib>
#endif

namespace walkrad {

namespace {
size_t whole_pages(size_t bytes) { return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes; }

// Each page written once, the 2 MiB blocks on all threads: the kernel zeroes a fresh page in the
// thread that first writes it, and the vector's own fill is one thread (the aggregation correction's
// arrays, made afresh each round: 3.5 s of one thread in the 150-room level's solve). The bytes stay
// 0, as the mapping gave them.
void first_touch(void* p, size_t size) {
  constexpr size_t kSmallPage = 4096;
  tbb::parallel_for(size_t(0), size / kHugePageBytes, [&](size_t block) {
    volatile char* at = static_cast<char*>(p) + block * kHugePageBytes;
    for (size_t o = 0; o < kHugePageBytes; o += kSmallPage) at[o] = 0;
  });
}
}  // namespace

void* allocate_huge(size_t bytes, bool touch) {
  const size_t size = whole_pages(bytes);
#if defined(__linux__)
  // Mapped 2 MiB larger and trimmed to a 2 MiB boundary: a huge page needs an aligned range.
  void* raw = mmap(nullptr, size + kHugePageBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t start = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = (start + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  if (aligned > start) munmap(raw, aligned - start);
  const uintptr_t end = start + size + kHugePageBytes;
  if (end > aligned + size) munmap(reinterpret_cast<void*>(aligned + size), end - (aligned + size));
  void* p = reinterpret_cast<void*>(aligned);
  madvise(p, size, MADV_HUGEPAGE);  // advice: ignored where the kernel has no huge pages to give
  if (touch) first_touch(p, size);
  return p;
#else
  void* p = std::aligned_alloc(kHugePageBytes, size);
  if (!p) throw std::bad_alloc();
  return p;
#endif
}

void free_huge(void* p, size_t bytes) {
#if defined(__linux__)
  munmap(p, whole_pages(bytes));
#else
  (void)bytes;
  std::free(p);
#endif
}

}  // namespace walkrad
