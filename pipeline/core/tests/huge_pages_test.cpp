#include "walkrad/core/huge_pages.h"

#include <cstdint>
#include <numeric>

#include <gtest/gtest.h>

namespace walkrad {
namespace {

// A block of 2 MiB and more starts on a 2 MiB boundary (a huge page needs one) and keeps what is
// written, through the copies of a growing vector; a small one comes from operator new.
TEST(HugePages, LargeArraysAreAlignedAndKeepTheirValues) {
  const size_t n = 3 * (kHugePageBytes / sizeof(uint64_t)) + 5;  // not a whole number of huge pages
  HugeVector<uint64_t> big(n);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(big.data()) % kHugePageBytes, 0u);
  std::iota(big.begin(), big.end(), uint64_t(1));
  for (int k = 0; k < 3; ++k) big.push_back(n + 1 + uint64_t(k));  // grows into a new mapping
  EXPECT_EQ(reinterpret_cast<uintptr_t>(big.data()) % kHugePageBytes, 0u);
  ASSERT_EQ(big.size(), n + 3);
  for (size_t k = 0; k < big.size(); ++k) ASSERT_EQ(big[k], k + 1) << k;
  HugeVector<uint64_t>().swap(big);

  HugeVector<double> small(100, 0.25);
  EXPECT_EQ(std::accumulate(small.begin(), small.end(), 0.0), 25.0);
}

}  // namespace
}  // namespace walkrad
