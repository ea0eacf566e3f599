#pragma once
// Large scratch buffers that are written in full before they are read (the simulated scans of a map: about 100 MB
// for a 1000 x 1000 map): no zero-filling, and backed by transparent huge pages where the kernel offers them for
// memory that asks (Linux, THP mode "madvise" or "always"). Each 4 KiB page of a fresh buffer costs a page fault;
// with 2 MiB pages a 100 MB buffer costs about 50 instead of 25 000.
#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

namespace gridtopo {

/// Asks the kernel to back [data, data + bytes) with transparent huge pages (madvise MADV_HUGEPAGE on the 2 MiB
/// pages the range covers whole). Call it before the memory is first written. A no-op for ranges under 2 MiB and
/// where the call is not available; never fails.
void adviseHugePages(void* data, std::size_t bytes);

/// From now on every cv::Mat of 4 MiB and more asks for transparent huge pages (adviseHugePages on its data; the
/// default allocator of OpenCV otherwise). For batch programs whose working set is many full-map images
/// (gridtopo-topology): the hospital map's run takes about 17 000 page faults instead of 390 000, and its TLB
/// misses fall. Contents and results do not change.
void adviseHugePagesForLargeImages();

/// Allocator for std::vector of trivial types: resize() leaves new elements uninitialised (default-initialised),
/// and blocks of 4 MiB and more are 2 MiB-aligned with adviseHugePages.
template <class T>
struct BulkAllocator {
  using value_type = T;
  static constexpr std::size_t kHugePage = std::size_t(2) << 20;

  BulkAllocator() = default;
  template <class U>
  BulkAllocator(const BulkAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < 2 * kHugePage) return static_cast<T*>(::operator new(bytes));
    void* p = ::operator new(bytes, std::align_val_t(kHugePage));
    adviseHugePages(p, bytes);
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < 2 * kHugePage)
      ::operator delete(p);
    else
      ::operator delete(p, std::align_val_t(kHugePage));
  }
  /// Default-initialises (no zero fill for trivial types); other constructions as usual.
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  template <class U>
  bool operator==(const BulkAllocator<U>&) const noexcept { return true; }
  template <class U>
  bool operator!=(const BulkAllocator<U>&) const noexcept { return false; }
};

}  // namespace gridtopo
