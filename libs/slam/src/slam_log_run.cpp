#include "gridtopo/slam/slam_log_run.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/slam/slam_run.h"

namespace gridtopo::slam {

namespace {
// What this process may hold: the least of the machine's memory, the cgroup's limit and the address-space limit.
std::size_t memoryLimitBytes() {
  std::size_t limit = SIZE_MAX;
  if (std::FILE* f = std::fopen("/proc/meminfo", "r")) {
    char key[64];
    unsigned long long kb = 0;
    while (std::fscanf(f, "%63s %llu kB", key, &kb) == 2)
      if (std::string(key) == "MemTotal:") limit = std::min<std::size_t>(limit, kb * 1024ULL);
    std::fclose(f);
  }
  if (std::FILE* f = std::fopen("/sys/fs/cgroup/memory.max", "r")) {
    unsigned long long bytes = 0;
    if (std::fscanf(f, "%llu", &bytes) == 1 && bytes > 0) limit = std::min<std::size_t>(limit, bytes);
    std::fclose(f);
  }
  struct rlimit rl {};
  if (::getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
    limit = std::min<std::size_t>(limit, rl.rlim_cur);
  return limit;
}

std::string gigabytes(double bytes) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f GB", bytes / 1e9);
  return b;
}
}  // namespace

std::size_t slamMemoryEstimateBytes(const SlamOptions& o) {
  return kSlamBaseBytes + static_cast<std::size_t>(o.particles) * kSlamBytesPerParticle;
}

void checkSlamMemory(const SlamOptions& o, std::size_t limit_bytes) {
  const std::size_t need = slamMemoryEstimateBytes(o);
  const std::size_t usable = limit_bytes / 10 * 9;  // the run's guard stops at 90%
  if (need > usable)
    throw InputError("[slam] particles",
                     std::to_string(o.particles) + " particles need at least " + gigabytes(need) + " (" +
                         std::to_string(kSlamBytesPerParticle / 1000) +
                         " kB per particle in the first steps of the Intel log), more than 90% of the " +
                         gigabytes(limit_bytes) + " this process may use: at most " +
                         std::to_string((usable - std::min(usable, kSlamBaseBytes)) / kSlamBytesPerParticle) +
                         " particles here (doc/guarantees.md, memory)");
}

SlamLogRunSummary runSlamOnLog(const SlamRunSpec& spec, bool quiet, std::ostream& log) {
  return runSlamOnLog(spec, quiet, log, memoryLimitBytes());
}

SlamLogRunSummary runSlamOnLog(const SlamRunSpec& spec, bool quiet, std::ostream& log, std::size_t limit) {
  checkOutputFolder(spec.output);  // an unusable -o is said now, not after the run
  checkSlamMemory(spec.options, limit);  // and a run that cannot fit
  if (!quiet) log << "options: " << (std::filesystem::path(spec.output) / "options.ini").string() << "\n";
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  const auto t0 = Clock::now();
  io::ScanLogInfo info;
  auto records = std::make_shared<std::vector<ScanRecord>>(io::readScanLog(spec.input, {}, info));
  // What the reader decided against the log's word is always said; which variant it read, unless quiet.
  for (const auto& w : info.warnings) log << "gridtopo-slam: warning: " << spec.input << ": " << w << "\n";
  if (!quiet)
    for (const auto& n : info.notes) log << "gridtopo-slam: note: " << spec.input << ": " << n << "\n";
  if (spec.max_scans > 0 && spec.max_scans < records->size()) records->resize(spec.max_scans);
  if (records->empty()) throw InputError(spec.input, "the log holds no laser scans");
  SlamLogRunSummary s;
  s.seconds_read = since(t0);

  auto owned_run = std::make_unique<SlamRun>(std::move(records), spec.options);
  SlamRun& run = *owned_run;
  ProgressBar bar(run.scanLimit(), "slam", "scans", quiet ? 0 : -1);
  // A run that outgrows the memory stops with a message, before the allocator fails somewhere inside it.
  const auto out_of_memory = [&](const std::string& how) {
    return std::runtime_error(how + " after " + std::to_string(run.scansFed()) + " of " +
                              std::to_string(run.scanLimit()) + " scans with " +
                              std::to_string(spec.options.particles) + " particles (resident " +
                              gigabytes(processMemory().rss_kb * 1024.0) + ", limit " + gigabytes(limit) +
                              "): run with fewer particles (doc/guarantees.md, memory)");
  };
  try {
    while (!run.atEnd()) {
      run.step();
      if ((run.scansFed() & 63) == 0) bar.update(run.scansFed());
      if (processMemory().rss_kb * 1024.0 > 0.9 * static_cast<double>(limit))
        throw out_of_memory("stopped at 90% of the memory this process may use");
    }
  } catch (const std::bad_alloc&) {
    throw out_of_memory("out of memory");
  }
  bar.update(run.scansFed());
  bar.finish();
  s.scans = run.scansFed();
  s.steps = run.filter().stepsProcessed();
  s.seconds_slam = run.filterSeconds();
  {
    // MRPT's maps and OpenCV's codecs (and the ~170 libraries they bring) are loaded for the outputs only, once the
    // particles, the loop closure and the scans outside the simple map are freed: the run's peak memory is the
    // filter's, or the outputs' with what they need.
    returnFreedMemoryFromNowOn();  // the particles' and the loop closure's memory leave the process as they go
    SlamResult result = run.finishResult(
        {"gridtopo-slam " + spec.input, "one pose per laser scan, best particle"}, slamRunIni(spec));
    owned_run.reset();
    keepOnlySimpleMapScans(result);
    writeSlamResultLoadingExport(spec.output, result);
  }
  s.seconds_total = since(t0);
  return s;
}

std::string slamLogRunSummaryLine(const SlamLogRunSummary& s, const std::string& output) {
  char line[512];
  std::snprintf(line, sizeof line,
                "gridtopo-slam: %zu scans, %zu processed, read %.2f s, slam %.2f s, total %.2f s, peak RSS %zu MB, "
                "output in ",
                s.scans, s.steps, s.seconds_read, s.seconds_slam, s.seconds_total, processMemory().peak_kb / 1024);
  return line + output + "\n";
}

}  // namespace gridtopo::slam
