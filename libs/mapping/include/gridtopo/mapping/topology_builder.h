#pragma once
// Topology as an MRPT map builder: a mrpt::slam::CMetricMapBuilder that wraps a metric map builder (gridtopo's RBPF,
// mapping::CMetricMapBuilderGridRbpf, by default; any CMetricMapBuilder whose metric map holds a COccupancyGridMap2D
// works), forwards every observation to it, and keeps the semantic and topological map of its current map: place
// labels, regions and the topological graph, recomputed every TopologyBuilderOptions::update_every processed scans
// or on request (updateTopology()). The topology is made by the one pipeline of gridtopo-topology
// (topology::occupancyForTopology, places::labelPlaces, topology::buildTopology) on the metric map thresholded as
// a SLAM grid (MapKind::ProbabilisticGrid), so it equals gridtopo-topology's on the map.gridmap.gz of the same
// map.
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/slam/CMetricMapBuilder.h>

#include <functional>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>

#include "gridtopo/core/map_image.h"
#include "gridtopo/mapping/topology_builder_options.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/model.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::mapping {

/// The semantic and topological map of one metric map.
struct MapTopology {
  places::OccupancyImage occ;          ///< the free space that was labelled (thresholded and opened as a SLAM grid)
  places::LabellingResult labelling;   ///< lattice, label distributions, labels before region correction
  topology::TopologyResult topo;       ///< labels after correction, regions, graph, segmentation
  MapImage map;                        ///< the map that was labelled (grey image, resolution, origin, SLAM grid kind)
  unsigned map_size = 0;               ///< the metric builder's getCurrentlyBuiltMapSize() when it was computed
  std::string source;                  ///< how errors and logs name the map ("<slam map, N scans>")

  /// Labels per map cell after correction (0 room, 1 corridor, 2 doorway, places::kNoLabel not free).
  const cv::Mat& labels() const { return topo.labels; }
  const topology::RegionMap& regions() const { return topo.regions; }
  const topology::TopologicalGraph& graph() const { return topo.graph; }
};

/// The semantic and topological map of an occupancy grid built by SLAM: the one topology pipeline with the grid's
/// free threshold and opening (TopologyOptions::freeThresholdFor / freeOpeningRadiusFor of
/// MapKind::ProbabilisticGrid). InputError (naming `source`) for a map without free cells.
/// `progress(stage, done, total)` as topology::topologyOfMap's.
/// `path`: where the robot was (world metres; MapImage::path), for the map preparation; empty when unknown.
MapTopology topologyOfSlamGrid(const mrpt::maps::COccupancyGridMap2D& grid, const places::PlacesModel& model,
                               const topology::TopologyOptions& options, const std::string& source,
                               const std::function<void(const std::string&, std::size_t, std::size_t)>& progress = {},
                               std::vector<cv::Point2d> path = {});

/// The robot's positions of a simple map (its keyframes' mean poses, world metres): the path the map
/// preparation weighs (CMetricMapBuilderTopology takes it from its metric builder's getCurrentlyBuiltMap).
std::vector<cv::Point2d> pathOfSimpleMap(const mrpt::maps::CSimpleMap& simplemap);

/// The builder's update step: the topology of a metric builder's map after `map_size` processed scans, named
/// "<slam map, N scans>", with MapTopology::map_size set. CMetricMapBuilderTopology (gridtopo-map) and the GUI's
/// live topology (session::LiveTopology) both make it with this call.
MapTopology topologyOfBuiltMap(const mrpt::maps::COccupancyGridMap2D& grid, unsigned map_size,
                               const places::PlacesModel& model, const topology::TopologyOptions& options,
                               const std::function<void(const std::string&, std::size_t, std::size_t)>& progress = {},
                               std::vector<cv::Point2d> path = {});

class CMetricMapBuilderTopology : public mrpt::slam::CMetricMapBuilder {
 public:
  /// `model`: the place model (gridtopo-train; required). `metric`: the builder to wrap; null = a
  /// mapping::CMetricMapBuilderGridRbpf with default SlamOptions.
  explicit CMetricMapBuilderTopology(std::shared_ptr<const places::PlacesModel> model,
                                     const topology::TopologyOptions& topology_options = topology::TopologyOptions(),
                                     const TopologyBuilderOptions& builder_options = TopologyBuilderOptions(),
                                     std::shared_ptr<mrpt::slam::CMetricMapBuilder> metric = nullptr);

  /// The schedule (loaded with TopologyBuilderOptions::loadFromConfigFile) and the pipeline's options; both may be
  /// changed between calls.
  TopologyBuilderOptions builderOptions;
  topology::TopologyOptions topologyOptions;
  /// Called after each recomputation (scheduled or requested), in the thread that made it.
  std::function<void(const MapTopology&)> onTopologyUpdated;

  /// Restarts the metric builder (forwarded) and forgets the topology.
  void initialize(const mrpt::maps::CSimpleMap& initialMap = mrpt::maps::CSimpleMap(),
                  const mrpt::poses::CPosePDF* x0 = nullptr) override;
  /// Forwarded; then the topology is recomputed if the map has grown past the next multiple of update_every.
  void processActionObservation(mrpt::obs::CActionCollection& action,
                                mrpt::obs::CSensoryFrame& observations) override;
  /// Observation-only rawlog layout. Forwarded to a CMetricMapBuilderGridRbpf as it is; for another metric builder,
  /// a CObservationOdometry is kept and each other observation is passed as a sensory frame with the odometry
  /// increment since the previous frame as its action. Then the schedule, as above.
  void processObservation(const mrpt::obs::CObservation::Ptr& obs);
  /// The metric builder's (forwarded).
  mrpt::poses::CPose3DPDF::Ptr getCurrentPoseEstimation() const override;
  void getCurrentlyBuiltMap(mrpt::maps::CSimpleMap& out_map) const override;
  unsigned int getCurrentlyBuiltMapSize() override;
  const mrpt::maps::CMultiMetricMap* getCurrentlyBuiltMetricMap() const override;
  void saveCurrentEstimationToImage(const std::string& file, bool formatEMF_BMP = true) override;

  /// Recomputes the semantic and topological map of the metric builder's current map now. InputError if its metric
  /// map holds no occupancy grid or the grid no free cell.
  void updateTopology();
  /// Recomputes it from `grid`, a map of `map_size` processed scans that the caller took from the metric builder
  /// (gridtopo-map: the final map, after the SLAM freed every particle but the best, so that the topology's memory
  /// does not add to the filter's).
  void updateTopologyOf(const mrpt::maps::COccupancyGridMap2D& grid, unsigned map_size,
                        std::vector<cv::Point2d> path);
  /// The last semantic and topological map (null before the first update). Safe to read from another thread: an
  /// update replaces the pointer, never the object.
  std::shared_ptr<const MapTopology> currentTopology() const;
  /// How many times the topology was computed since initialize().
  std::size_t topologyUpdates() const;

  mrpt::slam::CMetricMapBuilder& metricBuilder() { return *metric_; }
  const mrpt::slam::CMetricMapBuilder& metricBuilder() const { return *metric_; }

 private:
  void forwardOptions();
  void afterProcessing();

  std::shared_ptr<const places::PlacesModel> model_;
  std::shared_ptr<mrpt::slam::CMetricMapBuilder> metric_;
  mutable std::mutex topology_mutex_;
  std::shared_ptr<const MapTopology> topology_;
  std::size_t updates_ = 0;
  unsigned scheduled_bucket_ = 0;  ///< map size / update_every at the last scheduled update
  // The observation-only layout for metric builders that take sensory frames only.
  bool has_odometry_ = false, has_frame_odometry_ = false;
  mrpt::poses::CPose2D odometry_, frame_odometry_;
};

}  // namespace gridtopo::mapping
