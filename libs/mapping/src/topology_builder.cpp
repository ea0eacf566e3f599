#include "gridtopo/mapping/topology_builder.h"

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/core/map_image.h"
#include "gridtopo/mapping/rbpf_map_builder.h"

namespace gridtopo::mapping {

MapTopology topologyOfSlamGrid(const mrpt::maps::COccupancyGridMap2D& grid, const places::PlacesModel& model,
                               const topology::TopologyOptions& options, const std::string& source,
                               const std::function<void(const std::string&, std::size_t, std::size_t)>& progress,
                               std::vector<cv::Point2d> path) {
  // The same calls as gridtopo-topology on a .gridmap(.gz): a SLAM grid's free threshold and opening.
  MapTopology t;
  t.source = source;
  t.map = io::mapImageOfGrid(grid, MapKind::ProbabilisticGrid, source);
  t.map.path = std::move(path);
  topology::MapTopology run = topology::topologyOfMap(t.map, model, options, progress);
  t.occ = std::move(run.occ);
  t.labelling = std::move(run.labelling);
  t.topo = std::move(run.topo);
  return t;
}

std::vector<cv::Point2d> pathOfSimpleMap(const mrpt::maps::CSimpleMap& sm) {
  std::vector<cv::Point2d> path;
  path.reserve(sm.size());
  for (const auto& kf : sm) {
    if (!kf.pose) continue;
    const auto m = kf.pose->getMeanVal();
    path.emplace_back(m.x(), m.y());
  }
  return path;
}

MapTopology topologyOfBuiltMap(const mrpt::maps::COccupancyGridMap2D& grid, unsigned map_size,
                               const places::PlacesModel& model, const topology::TopologyOptions& options,
                               const std::function<void(const std::string&, std::size_t, std::size_t)>& progress,
                               std::vector<cv::Point2d> path) {
  MapTopology t = topologyOfSlamGrid(grid, model, options, "<slam map, " + std::to_string(map_size) + " scans>",
                                     progress, std::move(path));
  t.map_size = map_size;
  return t;
}

CMetricMapBuilderTopology::CMetricMapBuilderTopology(std::shared_ptr<const places::PlacesModel> model,
                                                     const topology::TopologyOptions& topology_options,
                                                     const TopologyBuilderOptions& builder_options,
                                                     std::shared_ptr<mrpt::slam::CMetricMapBuilder> metric)
    : builderOptions(builder_options),
      topologyOptions(topology_options),
      model_(std::move(model)),
      metric_(metric ? std::move(metric) : std::make_shared<mapping::CMetricMapBuilderGridRbpf>()) {
  if (!model_) throw std::invalid_argument("CMetricMapBuilderTopology: a place model is required");
}

void CMetricMapBuilderTopology::forwardOptions() {
  // CMetricMapBuilder::TOptions holds a reference (the verbosity level): copied field by field.
  metric_->options.enableMapUpdating = options.enableMapUpdating;
  metric_->options.debugForceInsertion = options.debugForceInsertion;
  metric_->options.alwaysInsertByClass = options.alwaysInsertByClass;
}

void CMetricMapBuilderTopology::initialize(const mrpt::maps::CSimpleMap& initialMap, const mrpt::poses::CPosePDF* x0) {
  forwardOptions();
  metric_->initialize(initialMap, x0);
  std::lock_guard<std::mutex> lock(topology_mutex_);
  topology_.reset();
  updates_ = 0;
  scheduled_bucket_ = 0;
  has_odometry_ = has_frame_odometry_ = false;
}

void CMetricMapBuilderTopology::processActionObservation(mrpt::obs::CActionCollection& action,
                                                         mrpt::obs::CSensoryFrame& observations) {
  forwardOptions();
  metric_->processActionObservation(action, observations);
  afterProcessing();
}

void CMetricMapBuilderTopology::processObservation(const mrpt::obs::CObservation::Ptr& obs) {
  if (!obs) return;
  forwardOptions();
  if (auto* ours = dynamic_cast<mapping::CMetricMapBuilderGridRbpf*>(metric_.get())) {
    ours->processObservation(obs);
  } else if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs)) {
    odometry_ = odo->odometry;
    has_odometry_ = true;
    return;
  } else {
    mrpt::obs::CActionCollection action;
    if (has_odometry_) {
      mrpt::obs::CActionRobotMovement2D mv;
      const mrpt::poses::CPose2D increment =
          has_frame_odometry_ ? odometry_ - frame_odometry_ : mrpt::poses::CPose2D();
      mv.computeFromOdometry(increment, mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
      mv.timestamp = obs->timestamp;
      action.insert(mv);
      frame_odometry_ = odometry_;
      has_frame_odometry_ = true;
    }
    mrpt::obs::CSensoryFrame frame;
    frame.insert(obs);
    metric_->processActionObservation(action, frame);
  }
  afterProcessing();
}

void CMetricMapBuilderTopology::afterProcessing() {
  if (builderOptions.update_every == 0) return;
  const unsigned bucket = metric_->getCurrentlyBuiltMapSize() / builderOptions.update_every;
  if (bucket <= scheduled_bucket_) return;
  scheduled_bucket_ = bucket;
  updateTopology();
}

void CMetricMapBuilderTopology::updateTopology() {
  const unsigned size = metric_->getCurrentlyBuiltMapSize();
  const std::string source = "<slam map, " + std::to_string(size) + " scans>";
  const mrpt::maps::CMultiMetricMap* maps = metric_->getCurrentlyBuiltMetricMap();
  const auto grid = maps ? maps->mapByClass<mrpt::maps::COccupancyGridMap2D>() : nullptr;
  if (!grid) throw InputError(source, "the metric map builder's map holds no occupancy grid (COccupancyGridMap2D)");
  // Where the robot was: the poses of the metric builder's simple map (any CMetricMapBuilder gives them).
  mrpt::maps::CSimpleMap sm;
  metric_->getCurrentlyBuiltMap(sm);
  updateTopologyOf(*grid, size, pathOfSimpleMap(sm));
}

void CMetricMapBuilderTopology::updateTopologyOf(const mrpt::maps::COccupancyGridMap2D& grid, unsigned size,
                                                 std::vector<cv::Point2d> path) {
  auto t = std::make_shared<const MapTopology>(
      topologyOfBuiltMap(grid, size, *model_, topologyOptions, {}, std::move(path)));
  {
    std::lock_guard<std::mutex> lock(topology_mutex_);
    topology_ = t;
    ++updates_;
  }
  if (onTopologyUpdated) onTopologyUpdated(*t);
}

std::shared_ptr<const MapTopology> CMetricMapBuilderTopology::currentTopology() const {
  std::lock_guard<std::mutex> lock(topology_mutex_);
  return topology_;
}

std::size_t CMetricMapBuilderTopology::topologyUpdates() const {
  std::lock_guard<std::mutex> lock(topology_mutex_);
  return updates_;
}

mrpt::poses::CPose3DPDF::Ptr CMetricMapBuilderTopology::getCurrentPoseEstimation() const {
  return metric_->getCurrentPoseEstimation();
}

void CMetricMapBuilderTopology::getCurrentlyBuiltMap(mrpt::maps::CSimpleMap& out_map) const {
  metric_->getCurrentlyBuiltMap(out_map);
}

unsigned int CMetricMapBuilderTopology::getCurrentlyBuiltMapSize() { return metric_->getCurrentlyBuiltMapSize(); }

const mrpt::maps::CMultiMetricMap* CMetricMapBuilderTopology::getCurrentlyBuiltMetricMap() const {
  return metric_->getCurrentlyBuiltMetricMap();
}

void CMetricMapBuilderTopology::saveCurrentEstimationToImage(const std::string& file, bool formatEMF_BMP) {
  metric_->saveCurrentEstimationToImage(file, formatEMF_BMP);
}

}  // namespace gridtopo::mapping
