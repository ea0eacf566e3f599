#include "gridtopo/slam/slam_result.h"

#include <sstream>

#include "gridtopo/core/lazy_library.h"
#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::slam {

std::string statsRow(const StepStats& s) {
  std::ostringstream o;
  o << s.step << ' ' << s.scan_index << ' ' << io::formatDouble(s.timestamp) << ' ' << s.time_s << ' ' << s.neff << ' '
    << (s.resampled ? 1 : 0) << ' ' << s.particles << ' ' << s.failed_matches << ' ' << s.evaluations << ' '
    << s.unique_tiles << ' ' << s.map_bytes << ' ' << s.lineages << ' ' << s.coalescence;
  return o.str();
}

void writeSlamResultLoadingExport(const std::string& dir, SlamResult& result) {
  using WriteFunction = void (*)(const std::string&, SlamResult&);
  lazyLibraryFunction<WriteFunction>("slam", "gridtopo_slam_write_result")(dir, result);
}

}  // namespace gridtopo::slam
