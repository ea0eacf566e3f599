#include "gridtopo/slam/slam_log_run.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/slam/slam_run.h"

namespace gridtopo::slam {

SlamLogRunSummary runSlamOnLog(const SlamRunSpec& spec, bool quiet, std::ostream& log) {
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

  SlamRun run(std::move(records), spec.options);
  ProgressBar bar(run.scanLimit(), "slam", "scans", quiet ? 0 : -1);
  run.runToEnd([&](std::size_t fed, std::size_t) { bar.update(fed); });
  bar.finish();
  s.scans = run.scansFed();
  s.steps = run.filter().stepsProcessed();
  s.seconds_slam = run.filterSeconds();
  run.finishAndWrite(spec.output, {"gridtopo-slam " + spec.input, "one pose per laser scan, best particle"},
                     slamRunIni(spec));
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
