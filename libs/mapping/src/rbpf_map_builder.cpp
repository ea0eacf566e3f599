#include "gridtopo/mapping/rbpf_map_builder.h"

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFParticles.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "gridtopo/io/scan_conversion.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/resampling.h"

namespace gridtopo::mapping {

using slam::compose;
using slam::Pose2;
using slam::RbpfSlam;
using slam::SlamOptions;
using slam::SlamRun;

CMetricMapBuilderGridRbpf::CMetricMapBuilderGridRbpf(const SlamOptions& options) : slamOptions(options) {
  initialize();
}

void CMetricMapBuilderGridRbpf::initialize(const mrpt::maps::CSimpleMap& initialMap,
                                           const mrpt::poses::CPosePDF* x0) {
  std::lock_guard<std::mutex> lock(critZoneChangingMap);
  run_ = std::make_unique<SlamRun>(slamOptions);
  RbpfSlam& filter = run_->filter();
  has_odometry_ = false;
  odometry_ = {0, 0, 0};
  if (x0) {
    const auto m = x0->getMeanVal();
    filter.setInitialPose({m.x(), m.y(), m.phi()});
  }
  for (const auto& [pose, sf] : initialMap) {
    if (!pose || !sf) continue;
    const auto p = pose->getMeanVal();
    for (const auto& o : *sf)
      if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(o))
        filter.insertKnownScan({p.x(), p.y(), p.yaw()}, io::fromMrptScan(*scan));
  }
}

void CMetricMapBuilderGridRbpf::feed(const mrpt::obs::CObservation& obs) {
  const auto* scan = dynamic_cast<const mrpt::obs::CObservation2DRangeScan*>(&obs);
  if (!scan) return;
  ScanRecord r;
  r.scan = io::fromMrptScan(*scan);
  r.has_odometry = has_odometry_;
  r.odometry = odometry_;
  r.source_index = run_->scansFed();
  if (options.enableMapUpdating) run_->feed(std::move(r));
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
  const auto& ps = run_->filter().particles();
  auto pdf = std::make_shared<mrpt::poses::CPose3DPDFParticles>(std::max<std::size_t>(1, ps.size()));
  if (ps.empty()) return pdf;
  std::vector<double> lw;
  for (const auto& p : ps) lw.push_back(p.log_weight);
  const auto w = slam::normalizedWeights(lw);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    pdf->m_particles[i].d = mrpt::math::TPose3D(ps[i].pose.x, ps[i].pose.y, 0, ps[i].pose.theta, 0, 0);
    pdf->m_particles[i].log_w = std::log(std::max(w[i], 1e-300));
  }
  return pdf;
}

void CMetricMapBuilderGridRbpf::getCurrentlyBuiltMap(mrpt::maps::CSimpleMap& out_map) const {
  out_map = run_->simpleMap();
}

unsigned int CMetricMapBuilderGridRbpf::getCurrentlyBuiltMapSize() {
  return static_cast<unsigned int>(run_->filter().stepsProcessed());
}

const mrpt::maps::CMultiMetricMap* CMetricMapBuilderGridRbpf::getCurrentlyBuiltMetricMap() const {
  metric_map_.maps.clear();
  const RbpfSlam& filter = run_->filter();
  if (!filter.particles().empty()) {
    // The run's map: with loop closure the map of the optimised poses.
    auto grid = std::make_shared<mrpt::maps::COccupancyGridMap2D>(toOccupancyGrid(run_->resultMap()));
    metric_map_.maps.push_back(grid);
  }
  return &metric_map_;
}

void CMetricMapBuilderGridRbpf::saveCurrentEstimationToImage(const std::string& file, bool /*formatEMF_BMP*/) {
  const RbpfSlam& filter = run_->filter();
  if (filter.particles().empty()) throw std::runtime_error("saveCurrentEstimationToImage: no map yet");
  const auto grid = toOccupancyGrid(run_->resultMap());
  if (!cv::imwrite(file, slam::renderMap(grid, run_->trajectory())))
    throw std::runtime_error("saveCurrentEstimationToImage: cannot write " + file);
}

}  // namespace gridtopo::mapping
