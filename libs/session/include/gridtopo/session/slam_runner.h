#pragma once
// Runs one SLAM run (gridtopo::slam::SlamRun, the scan loop gridtopo-slam drives too) on a log in a worker thread
// with play / pause / step / stop, and publishes read-only snapshots the GUI draws from. A snapshot shares the particle map tiles and the
// trajectory-tree nodes with the filter (both are immutable once shared: the map is copy-on-write and tree
// nodes are const), so taking one costs a few vector copies, never a map copy, and the GUI thread never reads
// memory the filter writes.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/slam/rbpf_slam.h"
#include "gridtopo/slam/slam_outputs.h"
#include "gridtopo/slam/slam_run.h"

namespace gridtopo::session {

enum class RunState { Paused, Running, Finished, Stopped, Failed };
const char* toString(RunState s);

struct ParticleView {
  slam::Pose2 pose;
  double weight = 0.0;            ///< normalised weight (sums to 1 over the particles)
  double log_weight_total = 0.0;  ///< accumulated log weight (the best particle has the largest)
  slam::TrajectoryNodePtr node;   ///< newest node of the particle's path (shared, immutable)
};

/// A loop closure of the run's pose graph (slam::LoopCloser::closures), its two ends at the graph's current poses.
struct ClosureView {
  std::size_t node = 0;         ///< the node whose scan closed the loop (the newest when it was found)
  std::size_t submap_node = 0;  ///< the first node of the older submap it matched
  slam::Pose2 newest, submap;   ///< their poses in the graph now (they move with every optimisation)
  bool rejected = false;        ///< left out of the graph by an optimisation (an outlier)
  bool global = false;          ///< found by the global search beyond the drift window (LoopClosureRecord::global)
};

struct SlamSnapshot {
  std::uint64_t version = 0;  ///< increases with every published snapshot
  RunState state = RunState::Paused;
  std::uint64_t commands = 0;  ///< the commands (play, pause, step, stop) taken when it was published
  std::string error;          ///< what() of the exception that stopped the run (state Failed)

  std::size_t scans_fed = 0;    ///< scans given to the filter so far
  std::size_t scans_total = 0;  ///< scans in the log
  std::size_t steps = 0;        ///< scans processed by the filter (update policy)
  double log_time = 0.0;        ///< timestamp of the last scan fed minus the first one (s)
  double log_duration = 0.0;    ///< last minus first timestamp of the log (s)

  std::vector<ParticleView> particles;
  std::size_t best = 0;        ///< index of the best particle
  slam::GridMap best_map;      ///< the best particle's; shares its tiles with the filter (copy-on-write)
  /// The pose of every scan fed so far (RbpfSlam::trajectory()); filled when the run pauses, ends, and at
  /// most every RunnerOptions::trajectory_interval seconds while running (see trajectory_scans).
  std::vector<TimedPose> trajectory;
  std::size_t trajectory_scans = 0;  ///< scans_fed when `trajectory` was computed
  std::vector<slam::StepStats> stats;  ///< one per processed scan

  bool loop_closure = false;           ///< the run has the loop closure ([loop_closure] enabled)
  std::vector<ClosureView> closures;   ///< every closure found so far, rejected ones too, in the order found
  /// Once the loop closure has closed a loop: every processed scan inserted at its optimised pose
  /// (SlamRun::resultMap), computed with `trajectory` when the run pauses or ends, and while running at most every
  /// trajectory_interval and no more than a tenth of the time (it re-inserts every scan); null before.
  std::shared_ptr<const slam::GridMap> optimised_map;
  std::size_t optimised_map_scans = 0;  ///< scans_fed when `optimised_map` was computed

  /// The run's map: the optimised one once a loop is closed, else the best particle's (what saveOutputs writes
  /// when the run is idle).
  const slam::GridMap& resultMap() const { return optimised_map ? *optimised_map : best_map; }

  std::size_t last_scan = 0;  ///< index of the last scan fed (valid when scans_fed > 0)
  slam::Pose2 last_scan_pose;  ///< best particle's pose for that scan (robot frame origin)

  double wall_seconds = 0.0;   ///< time spent running (excluding pauses)
  double scans_per_second = 0.0;
  double eta_seconds = 0.0;    ///< at the current rate; 0 when unknown
  std::size_t rss_bytes = 0;   ///< resident memory of the process
  std::size_t peak_rss_bytes = 0;
};

struct RunnerOptions {
  double snapshot_interval = 0.05;    ///< s between snapshots while running (the GUI draws at most this often)
  double trajectory_interval = 1.0;   ///< s between full-trajectory computations while running
  std::size_t max_scans = 0;          ///< feed at most this many scans (0 = the whole log)
};

class SlamRunner {
 public:
  /// Validates the options and builds the filter (throws gridtopo::InputError on bad options or an empty log).
  /// The runner starts paused; the worker thread waits for play() or step().
  SlamRunner(std::shared_ptr<const std::vector<ScanRecord>> scans, const slam::SlamOptions& options,
             const RunnerOptions& runner = {});
  ~SlamRunner();  ///< stops and joins the worker
  SlamRunner(const SlamRunner&) = delete;
  SlamRunner& operator=(const SlamRunner&) = delete;

  void play();                   ///< process scans continuously until the end of the log or pause()
  void pause();                  ///< pause after the scan in progress (a snapshot is published)
  void step(std::size_t n = 1);  ///< process scans until `n` more are processed by the filter, then pause
  void stop();                   ///< end the run for good (the filter keeps its state for saving)

  /// Blocks until the worker is paused, finished, stopped or failed, or `timeout` passes. True if it is.
  bool waitIdle(std::chrono::milliseconds timeout = std::chrono::milliseconds(600000)) const;

  std::shared_ptr<const SlamSnapshot> snapshot() const;
  std::uint64_t snapshotVersion() const { return version_.load(); }
  const slam::SlamOptions& options() const { return options_; }
  const std::vector<ScanRecord>& scans() const { return *scans_; }
  std::shared_ptr<const std::vector<ScanRecord>> scansPtr() const { return scans_; }
  std::size_t scanLimit() const { return limit_; }

  /// Writes the run's output set (slam::writeSlamOutputs, whole or nothing) into `dir`, with `trajectory_header`
  /// and `options_ini` (empty: the [slam] section alone). The worker must be idle (paused, finished, stopped): a
  /// std::runtime_error otherwise, or when no scan has been processed yet. The run can go on afterwards.
  void saveOutputs(const std::string& dir, const std::vector<std::string>& trajectory_header,
                   const std::string& options_ini = "") const;

  /// Receives the best particle's map (its tiles shared with the filter, copy-on-write: taking it is cheap), the
  /// filter's processed scans it holds (slam::RbpfSlam::stepsProcessed, the snapshot's `steps`) and the scans fed
  /// so far (the snapshot's `scans_fed`). Called on the worker thread: it must return quickly.
  /// `path`: where the robot was (world x, y of every processed scan; the topology's map preparation weighs it): the
  /// best particle's poses while running, the run's result (its simple map, as gridtopo-map's) at the end.
  using BestMapListener = std::function<void(const slam::GridMap& best_map, std::size_t steps, std::size_t scans_fed,
                                             std::vector<cv::Point2d> path)>;
  /// The worker calls `listener` each time the filter has processed a multiple of `every` scans (0: never on
  /// schedule), and when the run pauses, ends or stops, before the snapshot that shows it is published (so once
  /// waitIdle() returns, the listener has had the map of the idle run); never twice for one scan count. An empty
  /// listener detaches; when this returns, the previous listener is not running and is not called again.
  void setBestMapListener(std::size_t every, BestMapListener listener);

 private:
  void notifyListener(bool idle);  // worker only
  void run();
  /// `idle`: the run is paused or over (not a snapshot taken while running).
  void publish(bool with_trajectory, bool idle = true);
  bool idle() const;  // requires mu_

  std::shared_ptr<const std::vector<ScanRecord>> scans_;
  slam::SlamOptions options_;
  RunnerOptions ropt_;
  std::size_t limit_ = 0;
  // Touched by the worker while running, by the constructor, and by saveOutputs while the worker is idle.
  std::unique_ptr<slam::SlamRun> run_;

  mutable std::mutex mu_;
  mutable std::condition_variable cv_;  // commands -> worker, and worker -> waitIdle
  RunState state_ = RunState::Paused;
  bool quit_ = false;
  std::size_t pending_steps_ = 0;  // >0: step mode
  std::uint64_t commands_ = 0;     // commands taken: a snapshot from before the last one is not its acknowledgement
  /// Idle, and the snapshot published after the last command shows it (mu_ held).
  bool acknowledged() const;
  std::shared_ptr<const SlamSnapshot> snapshot_;
  std::atomic<std::uint64_t> version_{0};

  // worker-only
  std::chrono::steady_clock::time_point last_snapshot_{}, last_trajectory_{};
  std::size_t peak_rss_ = 0;
  std::vector<TimedPose> last_trajectory_poses_;
  std::size_t last_trajectory_scans_ = 0;
  std::shared_ptr<const slam::GridMap> last_optimised_map_;
  std::size_t last_optimised_map_scans_ = 0;
  std::chrono::steady_clock::time_point last_optimised_map_time_{};
  double last_optimised_map_seconds_ = 0.0;  ///< how long the last one took
  std::string error_;
  std::mutex listener_mu_;  // held while the listener runs
  BestMapListener listener_;
  std::size_t listener_every_ = 0;
  std::size_t listener_steps_ = 0;  // steps at the last call (0: none)
  std::thread worker_;
};

}  // namespace gridtopo::session
