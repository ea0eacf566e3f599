#include "gridtopo/simtrain/training_map.h"

#include <cmath>

#include "gridtopo/io/map_io.h"
#include "gridtopo/places/occupancy.h"
#include "gridtopo/sim/grid_plan.h"
#include "gridtopo/slam/map_export.h"

namespace gridtopo::simtrain {

sim::SimOptions TrainingMapOptions::defaultLaser() {
  sim::SimOptions o;
  o.beams = 181;
  o.fov = M_PI;
  o.max_range = 30.0;
  o.range_sigma = 0.02;
  o.range_quantum = 0.01;
  o.dropout_probability = 0.002;
  o.sensor_pose = {0.0, 0.0, 0.0};
  o.scan_spacing = 0.15;
  o.odo_sigma_xy = 0.02;
  o.odo_sigma_theta = 0.02;
  o.odo_sigma_theta_per_m = 0.01;
  o.odo_drift_theta = 0.01;
  o.seed = 1;
  return o;
}

cv::Mat mapInPlanFrame(const slam::GridMap& map, int rows, int cols) {
  // Through the SLAM's own export (MRPT grid, then the grey of map.png), placed cell by cell in the plan's frame.
  const double res = map.resolution();
  const auto grid = slam::toOccupancyGrid(map);
  const cv::Mat img = io::gridToImage(grid);
  const unsigned char unknown = img.at<unsigned char>(0, 0);  // the export's one-cell margin is never observed
  cv::Mat out(rows, cols, CV_8U, cv::Scalar(unknown));
  const int gw = img.cols, gh = img.rows;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int ix = grid.x2idx((c + 0.5) * res), iy = grid.y2idx((rows - r - 0.5) * res);
      if (ix < 0 || iy < 0 || ix >= gw || iy >= gh) continue;
      out.at<unsigned char>(r, c) = img.at<unsigned char>(gh - 1 - iy, ix);
    }
  return out;
}

cv::Mat mapAtTruePoses(const sim::SimLog& log, int rows, int cols, double res, const slam::MapUpdateOptions& map_o,
                       const slam::BeamOptions& beams) {
  slam::GridMap map(res);
  for (std::size_t i = 0; i < log.records.size(); ++i) {
    const auto ps = slam::prepareScan(log.records[i].scan, beams, res);
    const auto& t = log.truth[i];
    map.insertScan({t.x, t.y, t.phi}, ps.sensor, ps.map_beams, map_o);
  }
  return mapInPlanFrame(map, rows, cols);
}

TrainingMap simulateTrainingMap(const cv::Mat& plan_grey, const cv::Mat& codes, double res,
                                const TrainingMapOptions& o, const std::string& source,
                                const std::function<void(std::size_t, std::size_t)>& slam_progress) {
  const places::OccupancyImage occ = places::occupancyFromGrey(plan_grey, res, source);
  cv::Mat free = occ.cells == places::kFree;
  TrainingMap tm;
  tm.tour = planTour(free, codes, res, o.tour, source);
  std::vector<std::uint8_t> blocked(static_cast<std::size_t>(occ.rows()) * occ.cols());
  for (int r = 0; r < occ.rows(); ++r)
    for (int c = 0; c < occ.cols(); ++c) blocked[static_cast<std::size_t>(r) * occ.cols() + c] = !occ.isFree(r, c);
  const sim::GridPlan world(occ.rows(), occ.cols(), res, std::move(blocked));
  tm.log = sim::simulate([&world](double x, double y, double a) { return world.rayCast(x, y, a); }, tm.tour.waypoints,
                         o.laser);
  if (o.variant == MapVariant::Exact) {
    tm.grey = mapAtTruePoses(tm.log, occ.rows(), occ.cols(), res, o.map, o.beams);
    return tm;
  }
  // The SLAM variant: the same scans and odometry, the SLAM started at the known start pose, its map in the
  // plan's lattice (the plan's resolution: the SLAM's cells are the plan's pixels).
  slam::SlamOptions so = o.slam;
  so.resolution = res;
  SlamTrainingMap sm = runSlamInPlanFrame(tm.log, tm.log.truth.front(), occ.rows(), occ.cols(), so, slam_progress);
  tm.grey = std::move(sm.grey);
  tm.slam_trajectory = std::move(sm.trajectory);
  tm.slam_processed_scans = sm.processed_scans;
  tm.drift = measureSlamDrift(tm.grey, free, codes, res, tm.slam_trajectory, tm.log.truth);
  return tm;
}

}  // namespace gridtopo::simtrain
