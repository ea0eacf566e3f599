#pragma once
// One SLAM run: the scan records, the filter (RbpfSlam) fed one scan at a time or to the end, the rows of
// stats.txt (statsRow plus the process RSS), the time spent in the filter, and the run's output set
// (SlamOutputs, writeSlamOutputs). gridtopo-slam, the GUI's runner thread (with its play / pause / step) and the
// MRPT map builder (CMetricMapBuilderGridRbpf) all drive one, so the scan loop exists once.
//
// The class lives in libgridtopo_slam_core (no MRPT maps or observations) except its four members that give MRPT's
// types (simpleMap, outputs, finish, finishAndWrite): those are defined in libgridtopo_slam (slam_outputs.h), over
// the MRPT-free result (result, finishResult).

#include <cstddef>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <string>
#include <vector>

#include "gridtopo/core/scan_record.h"
#include "gridtopo/slam/loop_closure.h"
#include "gridtopo/slam/rbpf_slam.h"
#include "gridtopo/slam/slam_options.h"
#include "gridtopo/slam/slam_result.h"

namespace mrpt::maps {
class CSimpleMap;
}

namespace gridtopo::slam {

struct SlamOutputs;

class SlamRun {
 public:
  /// A run over a log read whole (shared with the caller, e.g. the GUI, which draws its scans): its first
  /// `max_scans` scans, 0 = all. Throws InputError on bad options ("<options>" [slam] key) or an empty log.
  SlamRun(std::shared_ptr<const std::vector<ScanRecord>> scans, const SlamOptions& options,
          std::size_t max_scans = 0);
  /// A run without a log, fed scan by scan with feed() (the MRPT map builder). It keeps the ranges of the
  /// processed scans only (what the simple map needs); the other records keep their time and odometry.
  explicit SlamRun(const SlamOptions& options);
  /// Drops the loop closure's queued steps and waits for the one in flight.
  ~SlamRun();
  SlamRun(const SlamRun&) = delete;
  SlamRun& operator=(const SlamRun&) = delete;

  /// The filter: for setInitialPose / insertKnownScan before the first scan, and for reading its state.
  RbpfSlam& filter();
  const RbpfSlam& filter() const;
  const SlamOptions& options() const { return options_; }

  /// Feeds the next scan of the log; true if the filter processed it (update policy). std::logic_error at the end.
  bool step();
  /// Feeds every remaining scan; `progress(fed, total)` every 64 scans and once at the end.
  void runToEnd(const std::function<void(std::size_t fed, std::size_t total)>& progress = {});
  /// A run without a log: appends `record` and feeds it. std::logic_error for a run over a log.
  bool feed(ScanRecord record);

  bool atEnd() const { return fed_ >= limit_; }
  std::size_t scansFed() const { return fed_; }
  /// The scans this run feeds: min(max_scans, log size), or the scans appended so far by feed().
  std::size_t scanLimit() const { return limit_; }
  const std::vector<ScanRecord>& scans() const { return *scans_; }
  /// Wall time spent in the filter (s), pauses excluded; the loop closure's included when it runs inline (one
  /// thread, or feedback), else only the time the filter waited for its queue.
  double filterSeconds() const { return filter_seconds_; }

  /// The loop closure beside the filter ([loop_closure] enabled), or null; up to date with every scan fed (its
  /// step in flight is waited for).
  const LoopCloser* loopCloser() const {
    waitForLoopCloser();
    return closer_.get();
  }
  /// The trajectory of every scan fed so far: through the pose graph's optimised poses with loop closure, else
  /// the filter's (RbpfSlam::trajectory).
  std::vector<TimedPose> trajectory() const;
  /// The map of the result: once the loop closure has closed a loop, every processed scan inserted at its optimised
  /// pose; before (or without loop closure) the best particle's map.
  GridMap resultMap() const;

  /// The text of stats.txt: "# " kStatsColumns " rss_kb", then one row per processed scan with the process's
  /// resident memory (kB) right after that scan.
  std::string statsText() const;
  /// The processed scans of the simple map and their poses: the loop closure's optimised poses of every processed
  /// scan, or (without loop closure) the best particle's path. Empty before the first processed scan.
  void simpleMapScans(std::vector<std::size_t>& scan_indices, std::vector<Pose2>& poses) const;
  /// The result so far (map, trajectory, closures, simple map's scans, texts); the run can go on.
  /// `options_ini` empty = slamOptionsIni(options()). std::runtime_error before the first processed scan.
  SlamResult result(const std::vector<std::string>& trajectory_header, const std::string& options_ini = "") const;
  /// The result at the end of a run, built so that the peak memory stays the filter's: the trajectory and the best
  /// particle are taken, every particle's map freed but the best one's (and the memory given back to the system),
  /// and only then the loop closure's map made. The run is over: it cannot be fed or asked for outputs again.
  SlamResult finishResult(const std::vector<std::string>& trajectory_header, const std::string& options_ini = "");

  // In libgridtopo_slam (MRPT's types; slam_outputs.h):
  /// The simple map of simpleMapScans (simpleMapAt).
  mrpt::maps::CSimpleMap simpleMap() const;
  /// exportSlamResult(result()): the output set of the run so far; the run can go on.
  SlamOutputs outputs(const std::vector<std::string>& trajectory_header, const std::string& options_ini = "") const;
  /// exportSlamResult(finishResult()): the output set at the end of a run (its map and pictures, 3 bytes a cell,
  /// made after the particles are freed).
  SlamOutputs finish(const std::vector<std::string>& trajectory_header, const std::string& options_ini = "");
  /// writeSlamResult(dir, finishResult()): the whole output set or nothing.
  void finishAndWrite(const std::string& dir, const std::vector<std::string>& trajectory_header,
                      const std::string& options_ini = "");
  bool finished() const { return !filter_; }

 private:
  bool feedNext();
  /// The loop closure's step after a processed scan, and the feedback of a large correction into the filter.
  void closeLoops(std::size_t index);
  void startLoopCloser();
  /// With more than one thread and without feedback, the loop closure's steps run in order on a thread of their own,
  /// up to kCloserQueue processed scans behind the filter: each step reads only its own copies (the scan, the
  /// motion) and the best particle's path as it was after its scan (an immutable trajectory node), so the results
  /// are those of the serial order, bit for bit. This waits until every queued step is done and rethrows the first
  /// error one threw (at every later call too: the steps after it are dropped).
  void waitForLoopCloser() const;
  void closerWorkerLoop();
  static constexpr std::size_t kCloserQueue = 64;
  /// Every processed scan inserted into a new map at the pose graph's current poses (feedback), or the scans
  /// `scan_indices` at `poses`.
  GridMap mapOfGraph() const;
  GridMap mapAt(const std::vector<std::size_t>& scan_indices, const std::vector<Pose2>& poses) const;
  /// Stops the loop closure's thread (its queued steps dropped, the one in flight waited for); idempotent.
  void stopLoopCloserThread();
  /// The loop closure has accepted a closure: the result is the pose graph's, not the best particle's.
  bool closedLoops() const { return closer_ && !closer_->closures().empty(); }
  /// result() and finishResult() but the map: trajectory, closures, stats, the simple map's scans, texts.
  /// `what` names the caller in the error of a finished run.
  SlamResult resultWithoutMap(const std::vector<std::string>& trajectory_header, const std::string& options_ini,
                              const char* what) const;
  /// The scan index of every node of the loop closure.
  std::vector<std::size_t> processedScanIndices() const;
  /// The accepted closures between the nodes' `poses`.
  std::vector<ClosureLine> closureLines(const std::vector<Pose2>& poses) const;
  void requireFilter(const char* what) const;

  SlamOptions options_;
  std::shared_ptr<const std::vector<ScanRecord>> scans_;
  std::shared_ptr<std::vector<ScanRecord>> appended_;  ///< the records of a run without a log (= *scans_)
  std::unique_ptr<RbpfSlam> filter_;
  std::unique_ptr<LoopCloser> closer_;
  /// The best particle's newest trajectory node after the processed scan of the loop closure's current step: its
  /// view of the filter (set by whichever thread runs the step).
  TrajectoryNodePtr closer_node_;
  // The loop closure's queue of steps and its thread (declared after closer_: they end first).
  mutable std::mutex closer_mutex_;
  mutable std::condition_variable closer_wake_, closer_done_;
  std::deque<std::function<void()>> closer_jobs_;
  bool closer_busy_ = false, closer_stop_ = false;
  std::exception_ptr closer_error_;
  std::thread closer_thread_;
  std::size_t feedbacks_ = 0;

  std::size_t limit_ = 0;
  std::size_t fed_ = 0;
  std::vector<std::size_t> rss_kb_;  ///< per processed scan
  double filter_seconds_ = 0.0;
};

}  // namespace gridtopo::slam
