#include "gridtopo/slam/map_builder.h"

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/poses/CPose3DPDFParticles.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "gridtopo/io/scan_conversion.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/resampling.h"

namespace gridtopo::slam {

CMetricMapBuilderGridRbpf::CMetricMapBuilderGridRbpf(const SlamOptions& options) : slamOptions(options) {
  initialize();
}

void CMetricMapBuilderGridRbpf::initialize(const mrpt::maps::CSimpleMap& initialMap,
                                           const mrpt::poses::CPosePDF* x0) {
  std::lock_guard<std::mutex> lock(critZoneChangingMap);
  filter_ = std::make_unique<RbpfSlam>(slamOptions);
  frames_.clear();
  has_odometry_ = false;
  odometry_ = {0, 0, 0};
  if (x0) {
    const auto m = x0->getMeanVal();
    filter_->setInitialPose({m.x(), m.y(), m.phi()});
  }
  for (const auto& [pose, sf] : initialMap) {
    if (!pose || !sf) continue;
    const auto p = pose->getMeanVal();
    for (const auto& o : *sf)
      if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(o))
        filter_->insertKnownScan({p.x(), p.y(), p.yaw()}, io::fromMrptScan(*scan));
  }
}

void CMetricMapBuilderGridRbpf::feed(const mrpt::obs::CObservation& obs) {
  const auto* scan = dynamic_cast<const mrpt::obs::CObservation2DRangeScan*>(&obs);
  if (!scan) return;
  io::ScanRecord r;
  r.scan = io::fromMrptScan(*scan);
  r.scan.timestamp = mrpt::Clock::toDouble(scan->timestamp);
  r.has_odometry = has_odometry_;
  r.odometry = odometry_;
  r.source_index = filter_->scansSeen();
  const std::size_t index = filter_->scansSeen();
  if (options.enableMapUpdating && filter_->processScan(r)) {
    auto sf = mrpt::obs::CSensoryFrame::Create();
    sf->insert(std::dynamic_pointer_cast<mrpt::obs::CObservation>(scan->duplicateGetSmartPtr()));
    frames_[index] = sf;
  }
}

void CMetricMapBuilderGridRbpf::processActionObservation(mrpt::obs::CActionCollection& action,
                                                         mrpt::obs::CSensoryFrame& observations) {
  std::lock_guard<std::mutex> lock(critZoneChangingMap);
  if (auto mv = action.getBestMovementEstimation()) {
    const mrpt::poses::CPose2D inc = mv->rawOdometryIncrementReading;
    const Pose2 next = compose({odometry_.x, odometry_.y, odometry_.phi}, {inc.x(), inc.y(), inc.phi()});
    odometry_ = {next.x, next.y, next.theta};
    has_odometry_ = true;
  }
  for (const auto& o : observations)
    if (o) feed(*o);
}

void CMetricMapBuilderGridRbpf::processObservation(const mrpt::obs::CObservation::Ptr& obs) {
  if (!obs) return;
  std::lock_guard<std::mutex> lock(critZoneChangingMap);
  if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs)) {
    odometry_ = {odo->odometry.x(), odo->odometry.y(), odo->odometry.phi()};
    has_odometry_ = true;
    return;
  }
  feed(*obs);
}

mrpt::poses::CPose3DPDF::Ptr CMetricMapBuilderGridRbpf::getCurrentPoseEstimation() const {
  const auto& ps = filter_->particles();
  auto pdf = std::make_shared<mrpt::poses::CPose3DPDFParticles>(std::max<std::size_t>(1, ps.size()));
  if (ps.empty()) return pdf;
  std::vector<double> lw;
  for (const auto& p : ps) lw.push_back(p.log_weight);
  const auto w = normalizedWeights(lw);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    pdf->m_particles[i].d = mrpt::math::TPose3D(ps[i].pose.x, ps[i].pose.y, 0, ps[i].pose.theta, 0, 0);
    pdf->m_particles[i].log_w = std::log(std::max(w[i], 1e-300));
  }
  return pdf;
}

void CMetricMapBuilderGridRbpf::getCurrentlyBuiltMap(mrpt::maps::CSimpleMap& out_map) const {
  out_map.clear();
  if (filter_->particles().empty()) return;
  for (const TrajectoryNode* n : pathOf(filter_->bestParticle().node)) {
    const auto it = frames_.find(n->scan_index);
    if (it == frames_.end()) continue;
    auto pose = std::make_shared<mrpt::poses::CPose3DPDFGaussian>(
        mrpt::poses::CPose3D(n->pose.x, n->pose.y, 0, n->pose.theta, 0, 0));
    out_map.insert(pose, it->second);
  }
}

unsigned int CMetricMapBuilderGridRbpf::getCurrentlyBuiltMapSize() {
  if (filter_->particles().empty()) return 0;
  unsigned int n = 0;
  for (const TrajectoryNode* node : pathOf(filter_->bestParticle().node)) n += frames_.count(node->scan_index) > 0;
  return n;
}

const mrpt::maps::CMultiMetricMap* CMetricMapBuilderGridRbpf::getCurrentlyBuiltMetricMap() const {
  metric_map_.maps.clear();
  if (!filter_->particles().empty()) {
    auto grid = std::make_shared<mrpt::maps::COccupancyGridMap2D>(toOccupancyGrid(filter_->bestParticle().map));
    metric_map_.maps.push_back(grid);
  }
  return &metric_map_;
}

void CMetricMapBuilderGridRbpf::saveCurrentEstimationToImage(const std::string& file, bool /*formatEMF_BMP*/) {
  if (filter_->particles().empty()) throw std::runtime_error("saveCurrentEstimationToImage: no map yet");
  const auto grid = toOccupancyGrid(filter_->bestParticle().map);
  if (!cv::imwrite(file, renderMap(grid, filter_->trajectory())))
    throw std::runtime_error("saveCurrentEstimationToImage: cannot write " + file);
}

}  // namespace gridtopo::slam
