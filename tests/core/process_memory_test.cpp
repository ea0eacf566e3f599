#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "gridtopo/core/process_memory.h"

using namespace gridtopo;

// Touching 64 MB raises the resident memory and its peak by about that much; freeing it and giving it back
// lowers the resident memory again while the peak stays.
TEST(ProcessMemory, FollowsAnAllocationAndItsRelease) {
  const ProcessMemory before = processMemory();
  ASSERT_GT(before.rss_kb, 0u);
  EXPECT_GE(before.peak_kb, before.rss_kb);
  constexpr std::size_t kBytes = 64u << 20;
  {
    std::unique_ptr<char[]> block(new char[kBytes]);
    std::memset(block.get(), 1, kBytes);
    const ProcessMemory during = processMemory();
    EXPECT_GE(during.rss_kb, before.rss_kb + 60u * 1024u);
    EXPECT_GE(during.peak_kb, during.rss_kb);
    EXPECT_EQ(block[kBytes - 1], 1);
  }
  releaseFreedMemory();
  const ProcessMemory after = processMemory();
  EXPECT_LT(after.rss_kb, before.rss_kb + 16u * 1024u);
  EXPECT_GE(after.peak_kb, before.rss_kb + 60u * 1024u);
}
