#pragma once
// gridtopo's RBPF SLAM (slam::SlamRun) as an MRPT map builder: usable from any MRPT program that drives a
// mrpt::slam::CMetricMapBuilder (rawlog loops, rbpf-slam-like tools, GUIs).
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/slam/CMetricMapBuilder.h>

#include <memory>

#include "gridtopo/slam/rbpf_slam.h"
#include "gridtopo/slam/slam_outputs.h"
#include "gridtopo/slam/slam_run.h"

namespace gridtopo::mapping {

class CMetricMapBuilderGridRbpf : public mrpt::slam::CMetricMapBuilder {
 public:
  explicit CMetricMapBuilderGridRbpf(const slam::SlamOptions& options = slam::SlamOptions());

  /// Options used by the next initialize() (loaded with slam::SlamOptions::loadFromConfigFile).
  slam::SlamOptions slamOptions;

  /// Restarts the filter. `initialMap`: its scans are inserted at their poses into every particle's map;
  /// `x0`: the pose of the first scan (its mean), default the first odometry pose.
  void initialize(const mrpt::maps::CSimpleMap& initialMap = mrpt::maps::CSimpleMap(),
                  const mrpt::poses::CPosePDF* x0 = nullptr) override;
  /// Particles (pose and log-weight) as a 3D particle PDF.
  mrpt::poses::CPose3DPDF::Ptr getCurrentPoseEstimation() const override;
  /// Action / sensory-frame rawlog layout: the odometry increment of the CActionRobotMovement2D is accumulated,
  /// every CObservation2DRangeScan of the frame is fed to the filter.
  void processActionObservation(mrpt::obs::CActionCollection& action,
                                mrpt::obs::CSensoryFrame& observations) override;
  /// Observation-only rawlog layout: CObservationOdometry sets the odometry, CObservation2DRangeScan is fed to
  /// the filter with the latest odometry; other observations are ignored.
  void processObservation(const mrpt::obs::CObservation::Ptr& obs);
  /// The processed scans along the best particle's path at its poses (slam::SlamRun::simpleMap, as gridtopo-slam
  /// writes map.simplemap).
  void getCurrentlyBuiltMap(mrpt::maps::CSimpleMap& out_map) const override;
  unsigned int getCurrentlyBuiltMapSize() override;
  /// The best particle's map as a CMultiMetricMap holding one COccupancyGridMap2D (rebuilt on each call).
  const mrpt::maps::CMultiMetricMap* getCurrentlyBuiltMetricMap() const override;
  /// Writes the best particle's map with its trajectory (the format follows the extension: .png, .bmp, ...;
  /// formatEMF_BMP is ignored, EMF is not supported).
  void saveCurrentEstimationToImage(const std::string& file, bool formatEMF_BMP = true) override;

  const slam::RbpfSlam& filter() const { return run_->filter(); }
  /// The run the builder feeds (its statistics rows, its output set: SlamRun::outputs, writeSlamOutputs).
  const slam::SlamRun& run() const { return *run_; }
  /// Ends the run and returns its output set with the run's memory-saving order (SlamRun::finish: every particle
  /// freed but the best before the map is made). The builder cannot be fed or asked for its map afterwards.
  slam::SlamOutputs finishRun(const std::vector<std::string>& trajectory_header, const std::string& options_ini = "") {
    return run_->finish(trajectory_header, options_ini);
  }

 private:
  void feed(const mrpt::obs::CObservation& obs);

  std::unique_ptr<slam::SlamRun> run_;
  bool has_odometry_ = false;
  mrpt::math::TPose2D odometry_{0, 0, 0};
  mutable mrpt::maps::CMultiMetricMap metric_map_;
};

}  // namespace gridtopo::mapping
