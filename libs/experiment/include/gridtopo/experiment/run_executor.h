#pragma once
// Runs the planned runs on this machine, up to `jobs` runs at a time: each run's folder gets its options.ini (and
// topology.ini), its processes (runStages: gridtopo-slam, gridtopo-topology, gridtopo-topology-compare) run one
// after the other, each one's output in RUN/<stage>.log; when the last ends (or one fails) the run is scored and recorded in
// RUN/result.json (ok, failed or crashed: a failed run does not stop the others). Runs already recorded as ok under
// the same id are skipped unless `force`. A stop request (SIGINT / SIGTERM with installStopHandlers) launches no
// further run, ends the running ones by their pids and records nothing for them, so that the next call resumes.
#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "gridtopo/experiment/run_plan.h"

namespace gridtopo::experiment {

struct ExecutionOptions {
  int jobs = 1;
  bool force = false;
  Executables exe;       ///< paths of gridtopo-slam, gridtopo-topology, gridtopo-topology-compare
  int progress = -1;     ///< progress bar over runs: -1 = on a TTY, 0 = off, 1 = on
  bool verbose = true;   ///< a line per finished run
};

struct ExecutionSummary {
  std::size_t selected = 0, skipped = 0, ok = 0, failed = 0, interrupted = 0;
  bool stopped = false;  ///< a stop request ended the execution early
};

/// Runs `indices` of plan.runs (all when empty). Unless it runs a single index, it holds a lock on
/// OUTPUT/.runner.lock: a second runner on the same results folder stops with an InputError.
ExecutionSummary executeRuns(const ExperimentPlan& plan, const std::vector<std::size_t>& indices,
                             const ExecutionOptions& options, std::ostream& log);

/// The default number of parallel runs: online cores / threads per run (0 threads = all cores), at least 1.
int defaultJobs(const ExperimentPlan& plan);

/// SIGINT and SIGTERM request a stop instead of ending the process.
void installStopHandlers();
void requestStop();
bool stopRequested();
void clearStopRequest();

}  // namespace gridtopo::experiment
