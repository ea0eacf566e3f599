#pragma once
// SLAM-like labelled training maps, made exactly (issue 15, item 1): a robot run through a labelled floor plan is
// simulated (plan_tour.h's path, a 180° laser with noise, no-return readings and drifting odometry, sim::GridPlan
// as the world), and the map is built from the simulated scans at their TRUE poses with the SLAM's own map update
// (slam::GridMap, the beam and map options of config-ini/slam.ini). The map is pixel-aligned with the plan, so the
// plan's labels are the map's labels, cell for cell, while the map carries the sensor's artefacts: unknown space
// behind walls and outside the building, rooms seen only through their doors, free rays through doors, walls
// blurred by range noise, no-return beams clearing free space.
#include <functional>
#include <opencv2/core.hpp>
#include <string>

#include "gridtopo/sim/simulator.h"
#include "gridtopo/simtrain/plan_tour.h"
#include "gridtopo/simtrain/slam_training_map.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/prepared_scan.h"

namespace gridtopo::simtrain {

/// How the map of the simulated run is made: `Exact`, the scans at their true poses (exact labels); `Slam`, the
/// SLAM's map of the same scans and odometry, started at the true start pose (slam_training_map.h: labels land
/// where the SLAM put the cells).
enum class MapVariant { Exact, Slam };

struct TrainingMapOptions {
  MapVariant variant = MapVariant::Exact;
  TourOptions tour;
  sim::SimOptions laser = defaultLaser();
  slam::MapUpdateOptions map;   ///< gridtopo-slam's map update ([slam] map_log_odds_*)
  slam::BeamOptions beams;      ///< gridtopo-slam's beam handling ([slam] max_usable_range, no_return_range, ...)
  /// The SLAM of the Slam variant (every [slam] key; loadSlamMapOptions sets its map and beams to `map`, `beams`).
  slam::SlamOptions slam;
  /// A laser like the Intel log's: 181 beams over 180°, 30 m, 2 cm noise, centimetre readings, 0.2 % dropouts,
  /// a scan every 0.15 m or 0.15 rad, odometry with 2 % noise and a 0.01 rad/m heading drift.
  static sim::SimOptions defaultLaser();
};

struct TrainingMap {
  cv::Mat grey;        ///< CV_8U, the plan's size: the map as gridtopo-slam writes map.png (white free, grey 128 unknown)
  Tour tour;
  sim::SimLog log;     ///< the simulated run (true poses in `log.truth`, in the plan's frame)
  /// The Slam variant only: the SLAM's pose of every scan, its processed scans and its drift.
  std::vector<TimedPose> slam_trajectory;
  std::size_t slam_processed_scans = 0;
  SlamDrift drift;
};

/// `plan_grey`: the plan's occupancy image (free >= 250, as places::occupancyFromGrey); `codes`: its labels.
/// `slam_progress(fed, total)`: the SLAM's scans (Slam variant).
TrainingMap simulateTrainingMap(const cv::Mat& plan_grey, const cv::Mat& codes, double resolution,
                                const TrainingMapOptions& options, const std::string& source = "<plan>",
                                const std::function<void(std::size_t, std::size_t)>& slam_progress = {});

/// A SLAM grid (its cell (cx, cy) covers [cx res, (cx + 1) res) x [cy res, (cy + 1) res)) as a grey image of rows x
/// cols in the plan's frame (cell (cx, cy) = pixel (cx, rows - 1 - cy)), through gridtopo-slam's own export
/// (slam::toOccupancyGrid, io::gridToImage: grey = round(255 * (1 - p_occupied)), 128 unknown). Cells outside the
/// lattice are dropped; pixels the grid does not cover are unknown.
cv::Mat mapInPlanFrame(const slam::GridMap& map, int rows, int cols);

/// The map of `log`'s scans inserted at their true poses, as a grey image of rows x cols in the plan's frame
/// (cell (cx, cy) of the map = pixel (cx, rows - 1 - cy)), grey = round(255 * (1 - p_occupied)) as io::gridToImage.
cv::Mat mapAtTruePoses(const sim::SimLog& log, int rows, int cols, double resolution,
                       const slam::MapUpdateOptions& map, const slam::BeamOptions& beams);

}  // namespace gridtopo::simtrain
