// Large arrays made afresh again and again (the aggregation correction's per-node sums, each round's
// row sums) on transparent huge pages. A block of 2 MiB or more is mapped on its own, aligned to
// 2 MiB and advised madvise(MADV_HUGEPAGE): its first write faults once per 2 MiB, not once per
// 4 KiB page (on the project's machine a fresh 4 KiB page costs 11.6 µs, 68 times its writes:
// bench/page_fault_bench.cpp). Smaller blocks come from operator new. Where the
// kernel gives no huge pages (transparent_hugepage "never", or not Linux) the advice does nothing and
// the pages are ordinary ones. The contents are what std::vector makes them: no bits change.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace walkrad {

// bytes: as asked; the mapping is rounded up to whole 2 MiB. touch: each page written once, on all
// threads (for an array filled at once); else each page comes at its first write. Throws
// std::bad_alloc.
void* allocate_huge(size_t bytes, bool touch = true);
void free_huge(void* p, size_t bytes);
constexpr size_t kHugePageBytes = size_t(2) << 20;

template <class T, bool Touch = true>
struct HugePageAllocator {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = HugePageAllocator<U, Touch>;
  };
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U, Touch>&) {}
  T* allocate(size_t n) {
    if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
    const size_t bytes = n * sizeof(T);
    if (bytes < kHugePageBytes) return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
    return static_cast<T*>(allocate_huge(bytes, Touch));
  }
  void deallocate(T* p, size_t n) {
    const size_t bytes = n * sizeof(T);
    if (bytes < kHugePageBytes) ::operator delete(p, std::align_val_t(alignof(T)));
    else free_huge(p, bytes);
  }
  template <class U>
  bool operator==(const HugePageAllocator<U, Touch>&) const { return true; }
  template <class U>
  bool operator!=(const HugePageAllocator<U, Touch>&) const { return false; }
};

// Made at its size and filled at once: its pages are touched as it is allocated.
template <class T>
using HugeVector = std::vector<T, HugePageAllocator<T, true>>;
// Reserved ahead of its growth (the hierarchy's nodes): pages come 2 MiB at a time as it grows, and
// a reserve costs nothing until it is used.
template <class T>
using GrowingHugeVector = std::vector<T, HugePageAllocator<T, false>>;

}  // namespace walkrad
