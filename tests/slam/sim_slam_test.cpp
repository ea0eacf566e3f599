#include <gtest/gtest.h>

#include <cmath>

#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/rbpf_slam.h"
#include <opencv2/imgcodecs.hpp>

using namespace gridtopo;

namespace {
struct Errors {
  double mean_xy = 0, max_xy = 0, mean_th = 0;
};
Errors compare(const std::vector<io::TimedPose>& est, const std::vector<mrpt::math::TPose2D>& truth) {
  Errors e;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const double d = std::hypot(est[i].pose.x - truth[i].x, est[i].pose.y - truth[i].y);
    e.mean_xy += d;
    e.max_xy = std::max(e.max_xy, d);
    e.mean_th += std::abs(slam::wrapAngle(est[i].pose.phi - truth[i].phi));
  }
  e.mean_xy /= est.size();
  e.mean_th /= est.size();
  return e;
}
}  // namespace

TEST(SimulatedSlam, LoopAroundOfficeStaysCloseToGroundTruth) {
  const auto plan = sim::FloorPlan::officeLoop();
  sim::SimOptions so;
  const auto log = sim::simulate(plan, sim::officeLoopWaypoints(1), so);
  ASSERT_GT(log.records.size(), 300u);
  slam::SlamOptions o;
  o.particles = 15;
  slam::RbpfSlam slam(o);
  for (const auto& r : log.records) slam.processScan(r);
  const auto traj = slam.trajectory();
  ASSERT_EQ(traj.size(), log.records.size());
  std::vector<io::TimedPose> odo(log.records.size());
  for (std::size_t i = 0; i < odo.size(); ++i) odo[i].pose = log.records[i].odometry;
  if (std::getenv("GRIDTOPO_TEST_VERBOSE"))
    for (std::size_t i = 0; i < traj.size(); i += 25)
      std::printf("%zu est %.3f %.3f %.4f truth %.3f %.3f %.4f\n", i, traj[i].pose.x, traj[i].pose.y, traj[i].pose.phi,
                  log.truth[i].x, log.truth[i].y, log.truth[i].phi);
  const Errors e = compare(traj, log.truth), eo = compare(odo, log.truth);
  std::printf("slam: mean %.4f m max %.4f m %.3f deg; odometry: mean %.4f m max %.4f m; steps %zu\n", e.mean_xy,
              e.max_xy, e.mean_th * 180 / M_PI, eo.mean_xy, eo.max_xy, slam.stepsProcessed());
  if (const char* dir = std::getenv("GRIDTOPO_TEST_PICTURES"))
    cv::imwrite(std::string(dir) + "/sim_slam.png", slam::renderMap(slam::toOccupancyGrid(slam.bestParticle().map), traj));
  EXPECT_GT(eo.mean_xy, 0.3);  // the odometry really is bad
  EXPECT_LT(e.mean_xy, 0.05);
  EXPECT_LT(e.max_xy, 0.15);
  EXPECT_LT(e.mean_th, 0.5 * M_PI / 180);
}

TEST(SimulatedSlam, WorksWithoutOdometry) {
  const auto plan = sim::FloorPlan::officeLoop();
  sim::SimOptions so;
  so.scan_spacing = 0.05;  // without odometry the matcher needs small steps between scans
  auto wp = sim::officeLoopWaypoints(1);
  wp.resize(4);
  auto log = sim::simulate(plan, wp, so);
  for (auto& r : log.records) r.has_odometry = false;
  slam::SlamOptions o;
  o.particles = 8;
  o.no_odometry_period = 0.15;  // process a scan every 0.15 s (0.075 m at 0.5 m/s)
  slam::RbpfSlam slam(o);
  for (const auto& r : log.records) slam.processScan(r);
  const auto traj = slam.trajectory();
  // The map frame starts at identity without odometry: compare in the frame of the first true pose.
  const slam::Pose2 t0{log.truth[0].x, log.truth[0].y, log.truth[0].phi};
  double sum = 0, mx = 0;
  for (std::size_t i = 0; i < traj.size(); ++i) {
    const slam::Pose2 t = slam::relative(t0, {log.truth[i].x, log.truth[i].y, log.truth[i].phi});
    const double d = std::hypot(traj[i].pose.x - t.x, traj[i].pose.y - t.y);
    sum += d;
    mx = std::max(mx, d);
  }
  std::printf("no odometry: mean %.4f m max %.4f m over %zu scans, %zu steps\n", sum / traj.size(), mx, traj.size(),
              slam.stepsProcessed());
  EXPECT_LT(sum / traj.size(), 0.05);
  EXPECT_LT(mx, 0.25);
}

TEST(SimulatedSlam, HalfDegreeLaserWith361BeamsAndOffCentreMount) {
  const auto plan = sim::FloorPlan::officeLoop();
  sim::SimOptions so;
  so.beams = 361;  // 0.5 degree over 180 degrees
  so.sensor_pose = {0.2, -0.05, 0.1};
  so.seed = 11;
  auto wp = sim::officeLoopWaypoints(1);
  wp.resize(4);
  const auto log = sim::simulate(plan, wp, so);
  slam::SlamOptions o;
  o.particles = 10;
  slam::RbpfSlam slam(o);
  for (const auto& r : log.records) slam.processScan(r);
  const auto traj = slam.trajectory();
  const Errors e = compare(traj, log.truth);
  std::printf("361 beams: mean %.4f m max %.4f m %.3f deg\n", e.mean_xy, e.max_xy, e.mean_th * 180 / M_PI);
  EXPECT_LT(e.mean_xy, 0.05);
  EXPECT_LT(e.max_xy, 0.15);
}
