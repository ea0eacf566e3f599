#pragma once
// The process's memory as the kernel counts it (/proc/self/status), for the statistics of long runs, and giving
// freed heap pages back to the system.
#include <cstddef>

namespace gridtopo {

struct ProcessMemory {
  std::size_t rss_kb = 0;   ///< resident set size now (VmRSS)
  std::size_t peak_kb = 0;  ///< its peak so far (VmHWM)
};

/// The resident memory of this process; zeros where /proc/self/status is not available.
ProcessMemory processMemory();

/// Gives the pages of freed heap memory back to the system (glibc keeps them otherwise: many small blocks spread
/// over the heap stay mapped after they are freed). A no-op on other C libraries.
void releaseFreedMemory();

/// From now on, heap memory goes back to the system as it is freed, from every thread's arena (glibc: a fixed trim
/// threshold of 128 KiB instead of the dynamic one, which grows with the large blocks a program frees and let
/// another thread's arena keep tens of megabytes of freed memory resident that malloc_trim does not reach). For the
/// end of a batch run, before its large structures are freed and its outputs made. A no-op on other C libraries.
void returnFreedMemoryFromNowOn();

/// Keeps freed heap memory in the process for later allocations instead of giving it back to the system (glibc:
/// no mmap for large blocks, no trimming). For batch programs that allocate and free many large images in turn
/// (gridtopo-topology: every image of a map is tens of megabytes): each fresh large block costs a page fault per
/// 4 KiB and the kernel's zeroing, a reused one nothing. The resident memory then stays at its peak until exit. A
/// no-op on other C libraries.
void keepFreedMemoryForReuse();

}  // namespace gridtopo
