#include "gridtopo/session/slam_runner.h"

#include <algorithm>

#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/core/process_memory.h"

namespace gridtopo::session {

const char* toString(RunState s) {
  switch (s) {
    case RunState::Paused: return "paused";
    case RunState::Running: return "running";
    case RunState::Finished: return "finished";
    case RunState::Stopped: return "stopped";
    case RunState::Failed: return "failed";
  }
  return "?";
}

SlamRunner::SlamRunner(std::shared_ptr<const std::vector<ScanRecord>> scans, const slam::SlamOptions& options,
                       const RunnerOptions& runner)
    : scans_(std::move(scans)), options_(options), ropt_(runner) {
  run_ = std::make_unique<slam::SlamRun>(scans_, options_, ropt_.max_scans);
  limit_ = run_->scanLimit();
  publish(true);
  worker_ = std::thread([this] { run(); });
}

SlamRunner::~SlamRunner() {
  {
    std::lock_guard<std::mutex> lk(mu_);
    quit_ = true;
  }
  cv_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void SlamRunner::play() {
  std::lock_guard<std::mutex> lk(mu_);
  if (state_ != RunState::Paused) return;
  pending_steps_ = 0;
  state_ = RunState::Running;
  ++commands_;
  cv_.notify_all();
}

void SlamRunner::pause() {
  std::lock_guard<std::mutex> lk(mu_);
  if (state_ != RunState::Running) return;
  state_ = RunState::Paused;
  pending_steps_ = 0;
  ++commands_;
  cv_.notify_all();
}

void SlamRunner::step(std::size_t n) {
  std::lock_guard<std::mutex> lk(mu_);
  if (state_ != RunState::Paused || n == 0) return;
  pending_steps_ = n;
  state_ = RunState::Running;
  ++commands_;
  cv_.notify_all();
}

void SlamRunner::stop() {
  std::lock_guard<std::mutex> lk(mu_);
  if (state_ == RunState::Paused || state_ == RunState::Running) {
    state_ = RunState::Stopped;
    ++commands_;
    cv_.notify_all();
  }
}

bool SlamRunner::idle() const { return state_ != RunState::Running; }

bool SlamRunner::acknowledged() const {
  // The snapshot from before a step also says Paused: only one published after the command acknowledges it.
  return idle() && snapshot_ && snapshot_->state == state_ && snapshot_->commands == commands_;
}

bool SlamRunner::waitIdle(std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lk(mu_);
  // Idle means the worker has acknowledged: the state is not Running and the snapshot reflects it.
  return cv_.wait_for(lk, timeout, [&] { return acknowledged(); });
}

void SlamRunner::saveOutputs(const std::string& dir, const std::vector<std::string>& trajectory_header,
                             const std::string& options_ini) const {
  // Holding the lock keeps the worker where it is: idle and acknowledged (its snapshot shows the idle state), so it
  // does not touch the run until the next command, which cannot come while the lock is held.
  std::lock_guard<std::mutex> lk(mu_);
  if (!acknowledged()) throw std::runtime_error("pause the run before saving");
  slam::writeSlamOutputs(dir, run_->outputs(trajectory_header, options_ini));
}

void SlamRunner::setBestMapListener(std::size_t every, BestMapListener listener) {
  std::lock_guard<std::mutex> lk(listener_mu_);
  listener_every_ = every;
  listener_ = std::move(listener);
  listener_steps_ = 0;
}

void SlamRunner::notifyListener(bool idle) {
  std::lock_guard<std::mutex> lk(listener_mu_);
  if (!listener_) return;
  const slam::RbpfSlam& filter = run_->filter();
  const std::size_t steps = filter.stepsProcessed();
  if (steps == 0 || steps == listener_steps_ || filter.particles().empty()) return;
  if (!idle && (listener_every_ == 0 || steps % listener_every_ != 0)) return;
  listener_steps_ = steps;
  // At the end of the log, the run's result (with loop closure: the map of the optimised poses).
  if (run_->atEnd()) {
    // As gridtopo-map's final topology: every scan's pose of the run's result.
    std::vector<cv::Point2d> path;
    for (const TimedPose& p : run_->trajectory()) path.emplace_back(p.pose.x, p.pose.y);
    listener_(run_->resultMap(), steps, run_->scansFed(), std::move(path));
  } else {
    const auto& best = filter.particles()[filter.bestParticleIndex()];
    std::vector<cv::Point2d> path;
    for (const slam::TrajectoryNode* n = best.node.get(); n; n = n->parent.get()) path.emplace_back(n->pose.x, n->pose.y);
    std::reverse(path.begin(), path.end());
    listener_(best.map, steps, run_->scansFed(), std::move(path));
  }
}

std::shared_ptr<const SlamSnapshot> SlamRunner::snapshot() const {
  std::lock_guard<std::mutex> lk(mu_);
  return snapshot_;
}

void SlamRunner::publish(bool with_trajectory, bool idle) {
  // Called by the worker (or the constructor before the worker exists): reads the filter freely.
  const slam::RbpfSlam& filter = run_->filter();
  const std::size_t fed = run_->scansFed();
  auto s = std::make_shared<SlamSnapshot>();
  s->scans_fed = fed;
  s->scans_total = limit_;
  s->steps = filter.stepsProcessed();
  const auto& sc = *scans_;
  const double t_first = sc.front().scan.timestamp;
  s->log_duration = sc[limit_ - 1].scan.timestamp - t_first;
  if (fed > 0) {
    s->last_scan = fed - 1;
    s->log_time = sc[fed - 1].scan.timestamp - t_first;
  }
  const auto& ps = filter.particles();
  s->particles.reserve(ps.size());
  double max_lw = -1e300;
  for (const auto& p : ps) max_lw = std::max(max_lw, p.log_weight);
  double sum = 0;
  for (const auto& p : ps) sum += std::exp(p.log_weight - max_lw);
  for (const auto& p : ps)
    s->particles.push_back({p.pose, std::exp(p.log_weight - max_lw) / sum, p.log_weight_total, p.node});
  if (!ps.empty()) {
    s->best = filter.bestParticleIndex();
    s->best_map = ps[s->best].map;  // shares tiles
    s->last_scan_pose = ps[s->best].pose;
  }
  const slam::LoopCloser* closer = run_->loopCloser();
  s->loop_closure = closer != nullptr;
  if (closer) {
    // Every snapshot, so that the ends follow each optimisation and a closure rejected later turns grey: read from
    // the graph node by node (not LoopCloser::poses(), which copies every node), they cost about 2 µs a snapshot
    // for the 251 closures of Intel's first 3000 scans.
    const auto& graph = closer->graph();
    for (const auto& c : closer->closures())
      s->closures.push_back({c.node, c.submap_node, graph.pose(c.node), graph.pose(c.submap_node), c.rejected,
                              c.global});
  }
  if (with_trajectory || fed == limit_) {
    last_trajectory_poses_ = run_->trajectory();
    last_trajectory_scans_ = fed;
    // The optimised map re-inserts every processed scan (Intel, 8 particles: 40 ms at 600 nodes, 3000 scans, against
    // 2.4 s in the filter; it grows with the nodes), so it is made with the trajectory, and while running at most
    // once per kOptimisedMapCost times its own cost: it takes at most a tenth of the worker's time on long logs.
    // SlamRun::resultMap is the best particle's map until a loop is closed: the snapshot has best_map for that.
    constexpr double kOptimisedMapCost = 10.0;
    const auto now = std::chrono::steady_clock::now();
    if (closer && !closer->closures().empty() && !ps.empty() &&
        (idle || fed == limit_ ||
         std::chrono::duration<double>(now - last_optimised_map_time_).count() >=
             kOptimisedMapCost * last_optimised_map_seconds_)) {
      last_optimised_map_ = std::make_shared<const slam::GridMap>(run_->resultMap());
      last_optimised_map_scans_ = fed;
      last_optimised_map_time_ = std::chrono::steady_clock::now();
      last_optimised_map_seconds_ = std::chrono::duration<double>(last_optimised_map_time_ - now).count();
    }
    last_trajectory_ = std::chrono::steady_clock::now();
  }
  s->trajectory = last_trajectory_poses_;
  s->trajectory_scans = last_trajectory_scans_;
  s->optimised_map = last_optimised_map_;
  s->optimised_map_scans = last_optimised_map_scans_;
  s->stats = filter.stats();
  s->wall_seconds = run_->filterSeconds();
  if (s->wall_seconds > 0 && fed > 0) {
    s->scans_per_second = fed / s->wall_seconds;
    s->eta_seconds = (limit_ - fed) / s->scans_per_second;
  }
  const ProcessMemory memory = processMemory();
  s->rss_bytes = memory.rss_kb * 1024;
  s->peak_rss_bytes = memory.peak_kb * 1024;
  std::lock_guard<std::mutex> lk(mu_);
  s->state = state_;
  s->commands = commands_;
  s->error = error_;
  s->version = version_.load() + 1;
  snapshot_ = std::move(s);
  version_.store(snapshot_->version);
  last_snapshot_ = std::chrono::steady_clock::now();
  cv_.notify_all();
}

void SlamRunner::run() {
  using clock = std::chrono::steady_clock;
  for (;;) {
    {
      std::unique_lock<std::mutex> lk(mu_);
      // Idle: publish the state change once, then sleep until a command.
      cv_.wait(lk, [&] {
        return quit_ || state_ == RunState::Running || !snapshot_ || snapshot_->state != state_ ||
               snapshot_->commands != commands_;
      });
      if (quit_) return;
      if (state_ != RunState::Running) {
        lk.unlock();
        notifyListener(true);
        publish(true);
        continue;
      }
    }
    // One scan.
    bool processed = false;
    try {
      processed = run_->step();
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lk(mu_);
      error_ = e.what();
      state_ = RunState::Failed;
    }
    bool state_changed = false;
    {
      std::lock_guard<std::mutex> lk(mu_);
      if (state_ == RunState::Running) {
        if (run_->atEnd()) {
          state_ = RunState::Finished;
          state_changed = true;
        } else if (pending_steps_ > 0 && processed && --pending_steps_ == 0) {
          state_ = RunState::Paused;
          state_changed = true;
        }
      }
    }
    notifyListener(state_changed);
    const auto now = clock::now();
    if (state_changed) {
      publish(true);
    } else if (std::chrono::duration<double>(now - last_snapshot_).count() >= ropt_.snapshot_interval) {
      publish(std::chrono::duration<double>(now - last_trajectory_).count() >= ropt_.trajectory_interval, false);
    }
  }
}

}  // namespace gridtopo::session
