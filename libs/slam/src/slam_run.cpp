#include "gridtopo/slam/slam_run.h"

#include <chrono>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/slam/options_ini.h"
#include "gridtopo/slam/prepared_scan.h"

namespace gridtopo::slam {

SlamRun::SlamRun(std::shared_ptr<const std::vector<ScanRecord>> scans, const SlamOptions& options,
                 std::size_t max_scans)
    : options_(options), scans_(std::move(scans)) {
  if (!scans_ || scans_->empty()) throw InputError("<log>", "the log holds no laser scans");
  options_.validate("<options>", "slam");
  limit_ = max_scans ? std::min(max_scans, scans_->size()) : scans_->size();
  filter_ = std::make_unique<RbpfSlam>(options_);
  startLoopCloser();
}

SlamRun::SlamRun(const SlamOptions& options)
    : options_(options), appended_(std::make_shared<std::vector<ScanRecord>>()) {
  options_.validate("<options>", "slam");
  scans_ = appended_;
  filter_ = std::make_unique<RbpfSlam>(options_);
  startLoopCloser();
}

SlamRun::~SlamRun() { stopLoopCloserThread(); }

void SlamRun::stopLoopCloserThread() {
  if (!closer_thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(closer_mutex_);
    closer_stop_ = true;
    closer_jobs_.clear();  // nobody will read their results
  }
  closer_wake_.notify_all();
  closer_thread_.join();
}

void SlamRun::closerWorkerLoop() {
  std::unique_lock<std::mutex> lock(closer_mutex_);
  for (;;) {
    closer_wake_.wait(lock, [&] { return closer_stop_ || !closer_jobs_.empty(); });
    if (closer_jobs_.empty()) return;  // stopping, nothing left
    std::function<void()> job = std::move(closer_jobs_.front());
    closer_jobs_.pop_front();
    const bool failed = closer_error_ != nullptr;  // after an error the remaining steps are dropped
    closer_busy_ = true;
    lock.unlock();
    std::exception_ptr err;
    try {
      if (!failed) job();
    } catch (...) {
      err = std::current_exception();
    }
    lock.lock();
    if (err && !closer_error_) closer_error_ = err;
    closer_busy_ = false;
    closer_done_.notify_all();
  }
}

void SlamRun::waitForLoopCloser() const {
  if (!closer_thread_.joinable()) return;
  std::unique_lock<std::mutex> lock(closer_mutex_);
  closer_done_.wait(lock, [&] { return closer_jobs_.empty() && !closer_busy_; });
  // The error stays: the loop closure missed steps, and every later result would be built on it.
  if (closer_error_) std::rethrow_exception(closer_error_);
}

void SlamRun::requireFilter(const char* what) const {
  if (!filter_) throw std::logic_error(std::string("SlamRun::") + what + ": the run is finished");
}

RbpfSlam& SlamRun::filter() {
  requireFilter("filter");
  return *filter_;
}

const RbpfSlam& SlamRun::filter() const {
  requireFilter("filter");
  return *filter_;
}

bool SlamRun::feedNext() {
  const auto t0 = std::chrono::steady_clock::now();
  const bool processed = filter_->processScan((*scans_)[fed_]);
  if (processed && closer_) closeLoops(fed_);
  filter_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++fed_;
  if (processed) rss_kb_.push_back(processMemory().rss_kb);
  return processed;
}

void SlamRun::startLoopCloser() {
  if (!options_.loop_closure.enabled) return;
  closer_ = std::make_unique<LoopCloser>(options_.loop_closure, options_.motion);
  // The motion edges follow the best particle's path as it is at each optimisation: resampling has pruned it of
  // the lineages that died out since (a fixed-lag smoother's view of the filter's motion).
  closer_->setFilterPath([this] {
    std::vector<LoopCloser::FilterStep> path;
    for (const TrajectoryNode* n : pathOf(closer_node_)) path.push_back({n->estimate, n->matched});
    return path;
  });
}

void SlamRun::closeLoops(std::size_t index) {
  const TrajectoryNodePtr node = filter_->bestParticle().node;
  const Pose2 motion = node->parent ? relative(node->parent->estimate, node->estimate) : Pose2{};
  const ScanRecord& record = (*scans_)[index];
  // The odometry over the same step (from the previous processed scan), when both scans carry it.
  std::optional<Pose2> odometry;
  if (node->parent) {
    const ScanRecord& before = (*scans_)[node->parent->scan_index];
    if (record.has_odometry && before.has_odometry)
      odometry = relative({before.odometry.x, before.odometry.y, before.odometry.phi},
                          {record.odometry.x, record.odometry.y, record.odometry.phi});
  }
  if (filter_->threads() > 1 && !options_.loop_closure.feedback) {
    // On the loop closure's thread, beside the filter's next scans.
    std::unique_lock<std::mutex> lock(closer_mutex_);
    if (!closer_thread_.joinable()) closer_thread_ = std::thread([this] { closerWorkerLoop(); });
    closer_done_.wait(lock, [&] { return closer_jobs_.size() < kCloserQueue; });
    closer_jobs_.push_back([this, node, index, t = record.scan.timestamp, motion, odometry,
                            scan = filter_->lastPreparedScan()] {
      closer_node_ = node;
      closer_->addScan(index, t, node->estimate, motion, odometry ? &*odometry : nullptr, scan, node->matched);
    });
    lock.unlock();
    closer_wake_.notify_one();
    return;
  }
  closer_node_ = node;
  const LoopClosureStep step = closer_->addScan(index, record.scan.timestamp, node->estimate, motion,
                                                odometry ? &*odometry : nullptr, filter_->lastPreparedScan(),
                                                node->matched);
  if (!step.feedback) return;
  // The filter goes on from the optimised estimate: every particle moved by the correction that takes the best
  // particle's estimate to the optimised pose, in the map of the optimised poses.
  const Pose2 correction = compose(step.newest_after, relative(node->estimate, Pose2{}));
  filter_->applyCorrection(correction, mapOfGraph());
  closer_->noteFilterCorrection(correction);
  ++feedbacks_;
}

GridMap SlamRun::mapOfGraph() const { return mapAt(processedScanIndices(), closer_->poses()); }

GridMap SlamRun::mapAt(const std::vector<std::size_t>& scan_indices, const std::vector<Pose2>& poses) const {
  GridMap map(options_.resolution);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const PreparedScan ps = prepareScan((*scans_)[scan_indices[k]].scan, options_.beams, options_.resolution);
    map.insertScan(poses[k], ps.sensor, ps.map_beams, options_.map);
  }
  return map;
}

std::vector<TimedPose> SlamRun::trajectory() const {
  requireFilter("trajectory");
  waitForLoopCloser();
  if (!closer_ || filter_->particles().empty()) return filter_->trajectory();
  return filter_->trajectoryThrough(closer_->finalPoses());
}

GridMap SlamRun::resultMap() const {
  requireFilter("resultMap");
  waitForLoopCloser();
  if (filter_->particles().empty()) return GridMap(options_.resolution);
  return closedLoops() ? mapAt(processedScanIndices(), closer_->finalPoses()) : filter_->bestParticle().map;
}

bool SlamRun::step() {
  requireFilter("step");
  if (atEnd()) throw std::logic_error("SlamRun::step: every scan of the run has been fed");
  return feedNext();
}

void SlamRun::runToEnd(const std::function<void(std::size_t, std::size_t)>& progress) {
  requireFilter("runToEnd");
  while (!atEnd()) {
    if (progress && (fed_ & 63) == 0) progress(fed_, limit_);
    feedNext();
  }
  if (progress) progress(fed_, limit_);
}

bool SlamRun::feed(ScanRecord record) {
  requireFilter("feed");
  if (!appended_) throw std::logic_error("SlamRun::feed: this run reads its scans from a log (use step)");
  appended_->push_back(std::move(record));
  limit_ = appended_->size();
  const bool processed = feedNext();
  if (!processed) {  // only processed scans are ever read again (simpleMap)
    LaserScan& s = appended_->back().scan;
    std::vector<float>().swap(s.ranges);
    std::vector<std::uint8_t>().swap(s.valid);
  }
  return processed;
}

std::string SlamRun::statsText() const {
  requireFilter("statsText");
  waitForLoopCloser();
  const std::vector<StepStats>& st = filter_->stats();
  std::ostringstream out;
  out << "# " << kStatsColumns << " rss_kb\n";
  for (std::size_t i = 0; i < st.size(); ++i) out << statsRow(st[i]) << ' ' << rss_kb_[i] << '\n';
  if (closer_) out << closuresText(closer_->closures(), closer_->counts(), feedbacks_)
                    << loopClosureCpuText(closer_->counts());
  return out.str();
}

std::vector<std::size_t> SlamRun::processedScanIndices() const {
  std::vector<std::size_t> idx(closer_ ? closer_->nodes() : 0);
  for (std::size_t k = 0; k < idx.size(); ++k) idx[k] = closer_->scanIndexOf(k);
  return idx;
}

std::vector<ClosureLine> SlamRun::closureLines(const std::vector<Pose2>& poses) const {
  std::vector<ClosureLine> lines;
  if (!closer_) return lines;
  for (const LoopClosureRecord& c : closer_->closures())
    if (!c.rejected && c.node < poses.size() && c.submap_node < poses.size())
      lines.push_back({poses[c.submap_node], poses[c.node], c.global});
  return lines;
}

void SlamRun::simpleMapScans(std::vector<std::size_t>& scan_indices, std::vector<Pose2>& poses) const {
  requireFilter("simpleMapScans");
  waitForLoopCloser();
  scan_indices.clear();
  poses.clear();
  if (filter_->particles().empty()) return;
  if (closer_) {
    scan_indices = processedScanIndices();
    poses = closer_->finalPoses();
    return;
  }
  scansOfPath(filter_->bestParticle().node, scan_indices, poses);
}

SlamResult SlamRun::resultWithoutMap(const std::vector<std::string>& trajectory_header, const std::string& options_ini,
                                     const char* what) const {
  requireFilter(what);
  waitForLoopCloser();
  if (filter_->stepsProcessed() == 0) throw std::runtime_error("the run has not processed a scan yet");
  SlamResult r;
  const std::vector<Pose2> poses = closer_ ? closer_->finalPoses() : std::vector<Pose2>{};
  r.trajectory = closer_ ? filter_->trajectoryThrough(poses) : filter_->trajectory();
  r.closures = closureLines(poses);
  r.stats = statsText();
  r.scans = scans_;
  simpleMapScans(r.scan_indices, r.scan_poses);
  r.trajectory_header = trajectory_header;
  r.options_ini = options_ini.empty() ? slamOptionsIni(options_) : options_ini;
  return r;
}

SlamResult SlamRun::result(const std::vector<std::string>& trajectory_header, const std::string& options_ini) const {
  SlamResult r = resultWithoutMap(trajectory_header, options_ini, "result");
  // With the loop closure's poses the simple map's scans are every processed scan at those poses.
  r.map = closedLoops() ? mapAt(r.scan_indices, r.scan_poses) : filter_->bestParticle().map;
  return r;
}

SlamResult SlamRun::finishResult(const std::vector<std::string>& trajectory_header, const std::string& options_ini) {
  SlamResult r = resultWithoutMap(trajectory_header, options_ini, "finishResult");
  // The export needs only the result's map: the particles' maps and the loop closure (its submaps, correlation
  // grids and pose graph) are freed before the loop closure's map is built (and before the export makes the MRPT
  // grid and the pictures, 3 bytes a cell, and gridtopo-slam loads MRPT's maps for them), so that the peak memory is
  // the filter's, not filter + export. The best particle's map shares its tiles (cheap to keep); the loop closure's
  // map is built from the scans and the poses alone, so only after the particles are gone (hospital seed 1: peak RSS
  // 428 -> 349 MB, same outputs).
  std::optional<GridMap> best;
  if (!closedLoops()) best = filter_->bestParticle().map;
  stopLoopCloserThread();
  closer_.reset();
  filter_.reset();
  releaseFreedMemory();
  r.map = best ? std::move(*best) : mapAt(r.scan_indices, r.scan_poses);
  releaseFreedMemory();
  return r;
}

}  // namespace gridtopo::slam
