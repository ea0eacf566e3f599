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

/// The memory a run of `options` needs at least, from its particles (doc/guarantees.md, memory): a base plus
/// kSlamBytesPerParticle per particle, the peak resident memory per particle of the first 15 filter steps of the
/// Intel log (it grows with the steps: 495 kB per particle after 63 steps). A lower bound: a run refused by it
/// could not even get started. The base: the least peak of any run (one particle, one processed scan: 68 MB, most
/// of it the libraries loaded for the outputs), rounded down.
inline constexpr std::size_t kSlamBaseBytes = 60'000'000;
inline constexpr std::size_t kSlamBytesPerParticle = 280'000;
std::size_t slamMemoryEstimateBytes(const SlamOptions& options);
/// InputError("[slam] particles", "N particles need at least X GB ..., at most M particles here") when the estimate
/// exceeds 90% of `limit_bytes`.
void checkSlamMemory(const SlamOptions& options, std::size_t limit_bytes);

/// Runs `spec`: reads spec.input (the reader's warnings always go to `log`; its notes and the options' dump unless
/// `quiet`), keeps the first spec.max_scans scans, runs the filter with a progress bar on stderr (none when `quiet`)
/// and writes the output set to spec.output with slamRunIni(spec) as options.ini. InputError when the log holds no
/// laser scans. Refuses before reading the log when the output folder cannot be written (checkOutputFolder) or the
/// particles cannot fit in this process's memory (checkSlamMemory: the least of the machine's memory, the cgroup's
/// limit and RLIMIT_AS); stops with a message (std::runtime_error) when the run's resident memory passes 90% of it.
SlamLogRunSummary runSlamOnLog(const SlamRunSpec& spec, bool quiet, std::ostream& log);
/// The same with `memory_limit_bytes` in place of what this process may use (the guards' test).
SlamLogRunSummary runSlamOnLog(const SlamRunSpec& spec, bool quiet, std::ostream& log, std::size_t memory_limit_bytes);

/// "gridtopo-slam: N scans, M processed, read R s, slam S s, total T s, peak RSS P MB, output in DIR", newline.
std::string slamLogRunSummaryLine(const SlamLogRunSummary& summary, const std::string& output);

}  // namespace gridtopo::slam
