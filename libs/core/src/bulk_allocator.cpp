#include "gridtopo/core/bulk_allocator.h"

#include <opencv2/core/mat.hpp>

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace gridtopo {

void adviseHugePages(void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kPage = std::uintptr_t(2) << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kPage - 1) & ~(kPage - 1), last = (begin + bytes) & ~(kPage - 1);
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);  // advice only
#else
  (void)data, (void)bytes;
#endif
}

namespace {
// OpenCV's standard allocation, with adviseHugePages on every block of at least 4 MiB (its whole 2 MiB pages).
class HugePageMatAllocator : public cv::MatAllocator {
 public:
  cv::UMatData* allocate(int dims, const int* sizes, int type, void* data, size_t* step, cv::AccessFlag flags,
                         cv::UMatUsageFlags usage) const override {
    cv::UMatData* u = cv::Mat::getStdAllocator()->allocate(dims, sizes, type, data, step, flags, usage);
    // The block's owner (currAllocator) is the standard allocator: it frees it.
    if (u && !data && u->size >= (std::size_t(4) << 20)) adviseHugePages(u->origdata, u->size);
    return u;
  }
  bool allocate(cv::UMatData* u, cv::AccessFlag flags, cv::UMatUsageFlags usage) const override {
    return cv::Mat::getStdAllocator()->allocate(u, flags, usage);
  }
  void deallocate(cv::UMatData* u) const override { cv::Mat::getStdAllocator()->deallocate(u); }
};
}  // namespace

void adviseHugePagesForLargeImages() {
  static HugePageMatAllocator allocator;
  cv::Mat::setDefaultAllocator(&allocator);
}

}  // namespace gridtopo
