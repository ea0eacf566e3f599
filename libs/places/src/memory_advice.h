#pragma once
// Large scan and feature buffers (about 100 MB each for a 1000 x 1000 map) are touched once, page by page:
// with 4 KiB pages that is some 60 000 page faults per run (a tenth of the pipeline's CPU time was spent in
// the kernel). Asking for transparent huge pages before the first write cuts the faults 512-fold where the
// kernel allows it (THP "madvise" or "always"); elsewhere this does nothing. The data are unaffected.
#include <cstddef>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace gridtopo::places::detail {

inline void adviseHugePages(const void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(p) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)p, (void)bytes;
#endif
}

}  // namespace gridtopo::places::detail
