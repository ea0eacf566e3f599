#include "gridtopo/slam/slam_result.h"

#include <sstream>

#include "gridtopo/core/lazy_library.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::slam {

std::string statsRow(const StepStats& s) {
  std::ostringstream o;
  o << s.step << ' ' << s.scan_index << ' ' << io::formatDouble(s.timestamp) << ' ' << s.time_s << ' ' << s.neff << ' '
    << (s.resampled ? 1 : 0) << ' ' << s.particles << ' ' << s.failed_matches << ' ' << s.evaluations << ' '
    << s.unique_tiles << ' ' << s.map_bytes << ' ' << s.lineages << ' ' << s.coalescence;
  return o.str();
}

void keepOnlySimpleMapScans(SlamResult& result) {
  if (!result.scans || result.scans.use_count() != 1) return;
  auto kept = std::make_shared<std::vector<ScanRecord>>();
  kept->reserve(result.scan_indices.size());
  for (std::size_t& index : result.scan_indices) {
    kept->push_back((*result.scans)[index]);
    index = kept->size() - 1;
  }
  result.scans = std::move(kept);
  releaseFreedMemory();
}

void writeSlamResultLoadingExport(const std::string& dir, SlamResult& result) {
  using WriteFunction = void (*)(const std::string&, SlamResult&);
  lazyLibraryFunction<WriteFunction>("slam", "gridtopo_slam_write_result")(dir, result);
}

}  // namespace gridtopo::slam
