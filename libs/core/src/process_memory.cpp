#include "gridtopo/core/process_memory.h"

#include <fstream>
#include <sstream>
#include <string>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace gridtopo {

ProcessMemory processMemory() {
  ProcessMemory m;
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    std::istringstream in(line);
    std::string key;
    std::size_t kb = 0;
    in >> key >> kb;
    if (key == "VmRSS:") m.rss_kb = kb;
    if (key == "VmHWM:") m.peak_kb = kb;
  }
  return m;
}

void releaseFreedMemory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

void returnFreedMemoryFromNowOn() {
#if defined(__GLIBC__)
  mallopt(M_TRIM_THRESHOLD, 128 * 1024);
#endif
}

void keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);  // as an unsigned size: never trim
#endif
}

}  // namespace gridtopo
