#pragma once
// gridtopo-slam's run of a log: the log read, the filter run over its scans (SlamRun) with a progress bar, the
// output set written with the run's loadable INI, and the times of the three steps.
#include <cstddef>
#include <ostream>
#include <string>

#include "gridtopo/slam/slam_run_ini.h"

namespace gridtopo::slam {

struct SlamLogRunSummary {
  std::size_t scans = 0;  ///< scans fed to the filter
  std::size_t steps = 0;  ///< scans the filter processed (the others moved too little)
  double seconds_read = 0, seconds_slam = 0, seconds_total = 0;
};

/// Runs `spec`: reads spec.input (the reader's warnings always go to `log`; its notes and the options' dump unless
/// `quiet`), keeps the first spec.max_scans scans, runs the filter with a progress bar on stderr (none when `quiet`)
/// and writes the output set to spec.output with slamRunIni(spec) as options.ini. InputError when the log holds no
/// laser scans.
SlamLogRunSummary runSlamOnLog(const SlamRunSpec& spec, bool quiet, std::ostream& log);

/// "gridtopo-slam: N scans, M processed, read R s, slam S s, total T s, peak RSS P MB, output in DIR", newline.
std::string slamLogRunSummaryLine(const SlamLogRunSummary& summary, const std::string& output);

}  // namespace gridtopo::slam
