#include "gridtopo/slam/slam_run.h"

#include <chrono>
#include <sstream>
#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/options_ini.h"

namespace gridtopo::slam {

SlamRun::SlamRun(std::shared_ptr<const std::vector<ScanRecord>> scans, const SlamOptions& options,
                 std::size_t max_scans)
    : options_(options), scans_(std::move(scans)) {
  if (!scans_ || scans_->empty()) throw InputError("<log>", "the log holds no laser scans");
  options_.validate("<options>", "slam");
  limit_ = max_scans ? std::min(max_scans, scans_->size()) : scans_->size();
  filter_ = std::make_unique<RbpfSlam>(options_);
}

SlamRun::SlamRun(const SlamOptions& options)
    : options_(options), appended_(std::make_shared<std::vector<ScanRecord>>()) {
  options_.validate("<options>", "slam");
  scans_ = appended_;
  filter_ = std::make_unique<RbpfSlam>(options_);
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
  filter_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++fed_;
  if (processed) rss_kb_.push_back(processMemory().rss_kb);
  return processed;
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
  const std::vector<StepStats>& st = filter_->stats();
  std::ostringstream out;
  out << "# " << kStatsColumns << " rss_kb\n";
  for (std::size_t i = 0; i < st.size(); ++i) out << statsRow(st[i]) << ' ' << rss_kb_[i] << '\n';
  return out.str();
}

mrpt::maps::CSimpleMap SlamRun::simpleMap() const {
  requireFilter("simpleMap");
  if (filter_->particles().empty()) return {};
  return simpleMapOf(filter_->bestParticle().node, *scans_);
}

SlamOutputs SlamRun::outputs(const std::vector<std::string>& trajectory_header, const std::string& options_ini) const {
  requireFilter("outputs");
  if (filter_->stepsProcessed() == 0) throw std::runtime_error("the run has not processed a scan yet");
  SlamOutputs o;
  o.grid = toOccupancyGrid(filter_->bestParticle().map);
  o.trajectory = filter_->trajectory();
  o.trajectory_header = trajectory_header;
  o.simplemap = simpleMap();
  o.stats = statsText();
  o.options_ini = options_ini.empty() ? slamOptionsIni(options_) : options_ini;
  return o;
}

SlamOutputs SlamRun::finish(const std::vector<std::string>& trajectory_header, const std::string& options_ini) {
  requireFilter("finish");
  if (filter_->stepsProcessed() == 0) throw std::runtime_error("the run has not processed a scan yet");
  SlamOutputs o;
  o.trajectory = filter_->trajectory();
  o.stats = statsText();
  const TrajectoryNodePtr best_node = filter_->bestParticle().node;
  // The export needs only the best particle: the other particles' maps are freed before the map (and its
  // pictures, 3 bytes a cell) is built, so that the peak memory is the filter's, not filter + export.
  o.grid = [&] {
    const GridMap best_map = filter_->bestParticle().map;  // shares the tiles
    filter_.reset();
    releaseFreedMemory();
    return toOccupancyGrid(best_map);
  }();
  releaseFreedMemory();
  o.trajectory_header = trajectory_header;
  o.simplemap = simpleMapOf(best_node, *scans_);
  o.options_ini = options_ini.empty() ? slamOptionsIni(options_) : options_ini;
  return o;
}

void SlamRun::finishAndWrite(const std::string& dir, const std::vector<std::string>& trajectory_header,
                             const std::string& options_ini) {
  writeSlamOutputs(dir, finish(trajectory_header, options_ini));
}

}  // namespace gridtopo::slam
