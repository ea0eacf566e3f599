// core/bulk_allocator.h: big blocks 2 MiB-aligned (so whole huge pages can back them), vectors behave as vectors,
// and the advice is harmless on any range.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

#include "gridtopo/core/bulk_allocator.h"

using gridtopo::BulkAllocator;

TEST(BulkAllocator, BigBlocksAreHugePageAligned) {
  std::vector<std::uint16_t, BulkAllocator<std::uint16_t>> big;
  big.resize(std::size_t(16) << 20);  // 32 MiB
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % (std::uintptr_t(2) << 20), 0u);
  std::iota(big.begin(), big.end(), std::uint16_t(0));
  EXPECT_EQ(big[70000], static_cast<std::uint16_t>(70000));
  EXPECT_EQ(big.back(), static_cast<std::uint16_t>(big.size() - 1));
}

TEST(BulkAllocator, VectorsCopyCompareAndGrowAsUsual) {
  std::vector<int, BulkAllocator<int>> a{1, 2, 3};
  a.insert(a.end(), {4, 5});
  a.push_back(6);
  const std::vector<int, BulkAllocator<int>> b(a);
  EXPECT_EQ(a, b);
  a.resize(3);
  EXPECT_EQ(a.size(), 3u);
  EXPECT_EQ(a[2], 3);
  std::vector<int, BulkAllocator<int>> c(5, 7);  // value constructions still set the value
  EXPECT_EQ(std::accumulate(c.begin(), c.end(), 0), 35);
  // Growing a small vector into a big block keeps its contents.
  a.resize(std::size_t(4) << 20);
  EXPECT_EQ(a[0] + a[1] + a[2], 6);
}

TEST(BulkAllocator, AdviceOnAnyRangeIsHarmless) {
  std::vector<char> v(5 << 20, 'x');
  gridtopo::adviseHugePages(v.data(), 0);
  gridtopo::adviseHugePages(v.data() + 1, 100);
  gridtopo::adviseHugePages(v.data() + 3, v.size() - 3);
  EXPECT_EQ(v[12345], 'x');
}
