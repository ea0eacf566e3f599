#include "gridtopo/experiment/run_executor.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>
#include <thread>

#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/experiment/run_record.h"
#include "gridtopo/experiment/run_scoring.h"
#include "gridtopo/experiment/subprocess.h"
#include "gridtopo/experiment/topology_scoring.h"
#include "gridtopo/io/trajectory_io.h"

namespace fs = std::filesystem;

namespace gridtopo::experiment {
namespace {

volatile std::sig_atomic_t g_stop = 0;
extern "C" void onStopSignal(int) { g_stop = 1; }

std::string readText(const fs::path& p) {
  std::ifstream f(p);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct Running {
  std::size_t run;
  std::chrono::steady_clock::time_point start;
  std::string start_time;
  std::vector<RunStage> stages;
  std::size_t stage = 0;            ///< the one running
  double cpu_s = 0, peak_rss_mb = 0;  ///< of the stages that ended
};

/// The record of a run whose process ended with `pr`.
RunRecord finishRun(const ExperimentPlan& plan, const PlannedRun& run, const ProcessResult& pr,
                    const Running& started, RunScorer& scorer, const std::string& commit, const std::string& host) {
  const RunStage& stage = started.stages.at(started.stage);
  RunRecord r = recordOf(run);
  r.exit_code = pr.exit_code;
  r.signal = pr.signal;
  r.wall_s = pr.wall_s;
  r.cpu_s = pr.cpu_s;
  r.peak_rss_mb = pr.peak_rss_mb;
  r.commit = commit;
  r.host = host;
  r.start_time = started.start_time;
  r.trans_mean = r.trans_std = r.trans_max = r.rot_mean = r.rot_std = r.rot_max = NAN;
  r.trans_local_mean = r.trans_revisit_mean = NAN;
  r.label_accuracy = r.recall_room = r.recall_corridor = r.recall_doorway = NAN;
  r.seg_recall = r.seg_precision = r.graph_attached = r.graph_loops_closed = r.graph_plan_loops = NAN;
  const fs::path dir(run.dir), out = dir / "out", log = stage.log;
  const std::string which = started.stages.size() > 1 ? stage.name + ": " : "";
  if (pr.signal != 0) {
    r.status = "crashed";
    r.error = which + "killed by signal " + std::to_string(pr.signal) + " (" + strsignal(pr.signal) + ")";
    const std::string last = lastErrorLine(log.string());
    if (!last.empty()) r.error += "; last output: " + last;
  } else if (pr.exit_code != 0) {
    r.status = "failed";
    r.error = which + "exit code " + std::to_string(pr.exit_code);
    const std::string last = lastErrorLine(log.string());
    if (!last.empty()) r.error += ": " + last;
  } else {
    try {
      if (run.topology) scoreTopology((dir / "topology").string(), !run.plan.empty(), r);
      if (run.slam) {
      const auto steps = summarizeSteps(readText(out / "stats.txt"), (out / "stats.txt").string());
      r.steps = steps.steps;
      r.resamplings = steps.resamplings;
      const auto traj = io::readTrajectory((out / "trajectory.txt").string());
      const ErrorScores e = scorer.score(traj, run.log, run.relations);
      r.relations_scored = e.relations;
      if (e.relations > 0) {
        r.trans_mean = e.translational.mean;
        r.trans_std = e.translational.std;
        r.trans_max = e.translational.max;
        r.rot_mean = e.rotational.mean;
        r.rot_std = e.rotational.std;
        r.rot_max = e.rotational.max;
        if (e.local.translational.count > 0) r.trans_local_mean = e.local.translational.mean;
        if (e.revisit.translational.count > 0) r.trans_revisit_mean = e.revisit.translational.mean;
      }
      }
      r.status = "ok";
      if (!plan.spec.keep_maps)
        for (const char* f : {"map.png", "map_trajectory.png", "map.gridmap.gz", "map.pgm", "map.yaml", "map.simplemap"})
          fs::remove(out / f);
    } catch (const std::exception& e) {
      r.status = "failed";
      r.error = std::string("scoring: ") + e.what();
    }
  }
  return r;
}

std::string describe(const RunRecord& r) {
  std::ostringstream o;
  o << r.status << ' ' << r.label;
  if (r.hasErrors()) o << ": trans " << r.trans_mean << " m, rot " << r.rot_mean << " deg";
  o << ", " << static_cast<long>(std::lround(r.wall_s)) << " s";
  if (!r.ok()) o << " (" << r.error << ")";
  return o.str();
}

}  // namespace

void installStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}
void requestStop() { g_stop = 1; }
bool stopRequested() { return g_stop != 0; }
void clearStopRequest() { g_stop = 0; }

int defaultJobs(const ExperimentPlan& plan) {
  const long cores = std::max(1L, ::sysconf(_SC_NPROCESSORS_ONLN));
  int threads = 1;
  for (const auto& r : plan.runs) threads = std::max(threads, r.threads <= 0 ? static_cast<int>(cores) : r.threads);
  return static_cast<int>(std::max(1L, cores / threads));
}

ExecutionSummary executeRuns(const ExperimentPlan& plan, const std::vector<std::size_t>& indices,
                             const ExecutionOptions& options, std::ostream& log) {
  ExecutionSummary sum;
  std::vector<std::size_t> selected = indices;
  if (selected.empty())
    for (const auto& r : plan.runs) selected.push_back(r.index);
  sum.selected = selected.size();
  std::vector<std::size_t> todo;
  for (std::size_t i : selected) {
    RunRecord existing;
    if (!options.force && loadRecord(plan.runs.at(i), existing) && existing.ok()) {
      ++sum.skipped;
      continue;
    }
    todo.push_back(i);
  }
  if (sum.skipped && options.verbose)
    log << "gridtopo-experiment: " << sum.skipped << " of " << sum.selected
        << " runs already done (same parameters and inputs), skipped; --force reruns them\n";
  if (todo.empty()) return sum;

  // One runner per results folder at a time (Slurm tasks, which run one run each, share it).
  fs::create_directories(plan.output);
  const std::string lock_path = (fs::path(plan.output) / ".runner.lock").string();
  const int lock = indices.size() == 1 ? -1 : ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock >= 0 && ::flock(lock, LOCK_EX | LOCK_NB) != 0) {
    ::close(lock);
    throw InputError(plan.output, "another gridtopo-experiment is running in this results folder");
  }
  struct CloseLock {
    int fd;
    ~CloseLock() {
      if (fd >= 0) ::close(fd);
    }
  } close_lock{lock};

  const std::string commit = sourceCommit(), host = hostName();
  RunScorer scorer;
  ProgressBar bar(todo.size(), "experiment", "runs", options.progress);
  std::map<pid_t, Running> running;
  std::size_t next = 0, finished = 0;
  const int jobs = std::max(1, options.jobs);
  auto note = [&] {
    return "running " + std::to_string(running.size()) + ", failed " + std::to_string(sum.failed);
  };
  auto say = [&](const std::string& line) {
    if (!options.verbose) return;
    if (bar.enabled()) log << "\r\033[K";
    log << line << "\n";
    log.flush();
  };

  while (finished + sum.interrupted < todo.size()) {
    while (!stopRequested() && next < todo.size() && static_cast<int>(running.size()) < jobs) {
      const PlannedRun& run = plan.runs.at(todo[next++]);
      fs::remove_all(run.dir);
      fs::create_directories(run.dir);
      if (run.slam)
        writeTextFileAtomically((fs::path(run.dir) / "options.ini").string(), runIniText(plan, run, options.exe.slam));
      if (run.topology)
        writeTextFileAtomically((fs::path(run.dir) / "topology.ini").string(), topologyIniText(plan, run));
      Running r{run.index, std::chrono::steady_clock::now(), utcNow(), runStages(run, options.exe)};
      const pid_t pid = spawnProcess(r.stages.front().argv, r.stages.front().log);
      running.emplace(pid, r);
    }
    if (stopRequested() && !sum.stopped) {
      sum.stopped = true;
      for (const auto& [pid, r] : running) ::kill(pid, SIGTERM);
    }
    if (running.empty()) {
      sum.interrupted += todo.size() - next;  // never started
      next = todo.size();
      break;
    }
    ProcessResult pr;
    const pid_t pid = reapChild(-1, false, pr);
    if (pid <= 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      bar.update(finished, note());
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // not ours
    Running started = it->second;
    running.erase(it);
    const PlannedRun& run = plan.runs.at(started.run);
    if ((sum.stopped || stopRequested()) && pr.signal != 0) {  // ended by the stop request (or by the same Ctrl-C):
      ++sum.interrupted;                                          // no record, the next call reruns it
      say("interrupted " + run.label);
      continue;
    }
    started.cpu_s += pr.cpu_s;
    started.peak_rss_mb = std::max(started.peak_rss_mb, pr.peak_rss_mb);
    const bool more = pr.ok() && started.stage + 1 < started.stages.size();
    if (more && !stopRequested()) {  // the run's next process
      const RunStage& next_stage = started.stages.at(++started.stage);
      running.emplace(spawnProcess(next_stage.argv, next_stage.log), started);
      continue;
    }
    if (more) {  // stopped between two of its processes: no record, the next call reruns it
      ++sum.interrupted;
      say("interrupted " + run.label);
      continue;
    }
    pr.cpu_s = started.cpu_s;
    pr.peak_rss_mb = started.peak_rss_mb;
    pr.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started.start).count();
    const RunRecord rec = finishRun(plan, run, pr, started, scorer, commit, host);
    saveRecord(rec);
    ++finished;
    (rec.ok() ? sum.ok : sum.failed) += 1;
    say("[" + std::to_string(finished) + "/" + std::to_string(todo.size()) + "] " + describe(rec));
    bar.update(finished, note());
  }
  bar.finish();
  return sum;
}

}  // namespace gridtopo::experiment
