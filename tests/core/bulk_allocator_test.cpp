// core/bulk_allocator.h: big blocks 2 MiB-aligned (so whole huge pages can back them), vectors behave as vectors,
// and the advice is harmless on any range.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <string>
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

namespace {
// The VmFlags of the mapping of /proc/self/smaps that holds `p` ("" when not found).
std::string vmFlagsOf(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    unsigned long lo = 0, hi = 0;
    if (line.rfind("VmFlags:", 0) != 0 && std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2) {
      inside = a >= lo && a < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}
}  // namespace

TEST(BulkAllocator, LargeImagesAskForHugePagesAndKeepTheirContents) {
  gridtopo::adviseHugePagesForLargeImages();
  cv::Mat big(3000, 3000, CV_32S);  // 36 MB
  for (int y = 0; y < big.rows; ++y)
    for (int x = 0; x < big.cols; ++x) big.at<int>(y, x) = y * 7919 + x;
  const cv::Mat copy = big.clone();
  EXPECT_EQ(cv::countNonZero(big != copy), 0);
  EXPECT_EQ(copy.at<int>(2999, 2999), 2999 * 7919 + 2999);
  cv::Mat small(10, 10, CV_8U, cv::Scalar(3));  // below 4 MiB: the standard allocation
  EXPECT_EQ(cv::sum(small)[0], 300.0);
  // Where the kernel has transparent huge pages, the middle of the image's block carries the advice ("hg").
  if (std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled")) {
    const std::string flags = vmFlagsOf(big.ptr<int>(1500));
    ASSERT_FALSE(flags.empty());
    EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
  }
  big.release();
  cv::Mat::setDefaultAllocator(nullptr);  // OpenCV's own again for the other tests
}
