#include "gridtopo/session/slam_runner.h"

#include <fstream>
#include <sstream>

#include "gridtopo/core/error.h"

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

void processMemory(std::size_t& rss, std::size_t& peak) {
  rss = peak = 0;
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    std::istringstream in(line);
    std::string key;
    std::size_t kb = 0;
    in >> key >> kb;
    if (key == "VmRSS:") rss = kb * 1024;
    if (key == "VmHWM:") peak = kb * 1024;
  }
}

SlamRunner::SlamRunner(std::shared_ptr<const std::vector<io::ScanRecord>> scans, const slam::SlamOptions& options,
                       const RunnerOptions& runner)
    : scans_(std::move(scans)), options_(options), ropt_(runner) {
  if (!scans_ || scans_->empty()) throw InputError("<log>", "the log holds no laser scans");
  options_.validate("<options>", "slam");
  limit_ = ropt_.max_scans ? std::min(ropt_.max_scans, scans_->size()) : scans_->size();
  slam_ = std::make_unique<slam::RbpfSlam>(options_);
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
  cv_.notify_all();
}

void SlamRunner::pause() {
  std::lock_guard<std::mutex> lk(mu_);
  if (state_ != RunState::Running) return;
  state_ = RunState::Paused;
  pending_steps_ = 0;
  cv_.notify_all();
}

void SlamRunner::step(std::size_t n) {
  std::lock_guard<std::mutex> lk(mu_);
  if (state_ != RunState::Paused || n == 0) return;
  pending_steps_ = n;
  state_ = RunState::Running;
  cv_.notify_all();
}

void SlamRunner::stop() {
  std::lock_guard<std::mutex> lk(mu_);
  if (state_ == RunState::Paused || state_ == RunState::Running) {
    state_ = RunState::Stopped;
    cv_.notify_all();
  }
}

bool SlamRunner::idle() const { return state_ != RunState::Running; }

bool SlamRunner::waitIdle(std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lk(mu_);
  // Idle means the worker has acknowledged: the state is not Running and the snapshot reflects it.
  return cv_.wait_for(lk, timeout, [&] { return idle() && snapshot_ && snapshot_->state == state_; });
}

std::shared_ptr<const SlamSnapshot> SlamRunner::snapshot() const {
  std::lock_guard<std::mutex> lk(mu_);
  return snapshot_;
}

void SlamRunner::publish(bool with_trajectory) {
  // Called by the worker (or the constructor before the worker exists): reads the filter freely.
  auto s = std::make_shared<SlamSnapshot>();
  s->scans_fed = next_scan_;
  s->scans_total = limit_;
  s->steps = slam_->stepsProcessed();
  const auto& sc = *scans_;
  const double t_first = sc.front().scan.timestamp;
  s->log_duration = sc[limit_ - 1].scan.timestamp - t_first;
  if (next_scan_ > 0) {
    s->last_scan = next_scan_ - 1;
    s->log_time = sc[next_scan_ - 1].scan.timestamp - t_first;
  }
  const auto& ps = slam_->particles();
  s->particles.reserve(ps.size());
  double max_lw = -1e300;
  for (const auto& p : ps) max_lw = std::max(max_lw, p.log_weight);
  double sum = 0;
  for (const auto& p : ps) sum += std::exp(p.log_weight - max_lw);
  for (const auto& p : ps)
    s->particles.push_back({p.pose, std::exp(p.log_weight - max_lw) / sum, p.log_weight_total, p.node});
  if (!ps.empty()) {
    s->best = slam_->bestParticleIndex();
    s->best_map = ps[s->best].map;  // shares tiles
    s->last_scan_pose = ps[s->best].pose;
  }
  if (with_trajectory || next_scan_ == limit_) {
    last_trajectory_poses_ = slam_->trajectory();
    last_trajectory_scans_ = next_scan_;
    last_trajectory_ = std::chrono::steady_clock::now();
  }
  s->trajectory = last_trajectory_poses_;
  s->trajectory_scans = last_trajectory_scans_;
  s->stats = slam_->stats();
  s->wall_seconds = wall_;
  if (wall_ > 0 && next_scan_ > 0) {
    s->scans_per_second = next_scan_ / wall_;
    s->eta_seconds = (limit_ - next_scan_) / s->scans_per_second;
  }
  processMemory(s->rss_bytes, s->peak_rss_bytes);
  std::lock_guard<std::mutex> lk(mu_);
  s->state = state_;
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
      cv_.wait(lk, [&] { return quit_ || state_ == RunState::Running || !snapshot_ || snapshot_->state != state_; });
      if (quit_) return;
      if (state_ != RunState::Running) {
        lk.unlock();
        publish(true);
        continue;
      }
    }
    // One scan.
    const auto t0 = clock::now();
    bool processed = false;
    try {
      processed = slam_->processScan((*scans_)[next_scan_]);
      ++next_scan_;
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lk(mu_);
      error_ = e.what();
      state_ = RunState::Failed;
    }
    wall_ += std::chrono::duration<double>(clock::now() - t0).count();
    bool state_changed = false;
    {
      std::lock_guard<std::mutex> lk(mu_);
      if (state_ == RunState::Running) {
        if (next_scan_ >= limit_) {
          state_ = RunState::Finished;
          state_changed = true;
        } else if (pending_steps_ > 0 && processed && --pending_steps_ == 0) {
          state_ = RunState::Paused;
          state_changed = true;
        }
      }
    }
    const auto now = clock::now();
    if (state_changed) {
      publish(true);
    } else if (std::chrono::duration<double>(now - last_snapshot_).count() >= ropt_.snapshot_interval) {
      publish(std::chrono::duration<double>(now - last_trajectory_).count() >= ropt_.trajectory_interval);
    }
  }
}

}  // namespace gridtopo::session
