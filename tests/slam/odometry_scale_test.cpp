// Odometry calibration in the particle state (motion_scale_sigma, motion_scale_walk_sigma): every particle
// scales the translation of the odometry increments by its own factor.
#include <gtest/gtest.h>

#include <cmath>

#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/rbpf_slam.h"

using namespace gridtopo;

namespace {
sim::SimLog straightLog() {
  const auto plan = sim::FloorPlan::officeLoop();
  sim::SimOptions so;
  auto wp = sim::officeLoopWaypoints(1);
  wp.resize(3);
  return sim::simulate(plan, wp, so);
}

// Odometry proposal with (almost) no motion noise and no resampling: a particle's path is the odometry with
// its translation scaled by the particle's factor.
slam::SlamOptions deterministicMotion(double scale_sigma, double walk_sigma) {
  slam::SlamOptions o;
  o.particles = 40;
  o.threads = 2;
  o.proposal.type = slam::ProposalType::Odometry;
  o.resample_threshold = 0.0;
  o.motion.alpha_rr = o.motion.alpha_rt = o.motion.alpha_tt = o.motion.alpha_tr = 0.0;
  o.motion.min_sigma_xy = 1e-9;
  o.motion.min_sigma_theta = 1e-9;
  o.motion.scale_sigma = scale_sigma;
  o.motion.scale_walk_sigma = walk_sigma;
  return o;
}

double stddev(const std::vector<double>& v) {
  double m = 0.0, s = 0.0;
  for (double x : v) m += x;
  m /= static_cast<double>(v.size());
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}
}  // namespace

TEST(OdometryScale, OffKeepsEveryParticleAtScaleOne) {
  const auto log = straightLog();
  slam::RbpfSlam f(deterministicMotion(0.0, 0.0));
  for (const auto& r : log.records) f.processScan(r);
  for (const auto& p : f.particles()) EXPECT_EQ(p.odometry_scale, 1.0);
}

TEST(OdometryScale, EachParticleMovesByItsScaleTimesTheOdometry) {
  const auto log = straightLog();
  ASSERT_GT(log.records.size(), 30u);
  slam::RbpfSlam f(deterministicMotion(0.05, 0.0));
  for (const auto& r : log.records) f.processScan(r);
  ASSERT_GT(f.stepsProcessed(), 10u);
  std::vector<double> scales;
  for (const auto& p : f.particles()) {
    scales.push_back(p.odometry_scale);
    const auto path = slam::pathOf(p.node);
    ASSERT_EQ(path.size(), f.stepsProcessed());
    double odo_len = 0.0, path_len = 0.0;
    for (std::size_t k = 1; k < path.size(); ++k) {
      const auto& a = log.records[path[k - 1]->scan_index].odometry;
      const auto& b = log.records[path[k]->scan_index].odometry;
      const slam::Pose2 u = slam::relative({a.x, a.y, a.phi}, {b.x, b.y, b.phi});
      const slam::Pose2 d = slam::relative(path[k - 1]->pose, path[k]->pose);
      EXPECT_NEAR(d.x, p.odometry_scale * u.x, 1e-6);
      EXPECT_NEAR(d.y, p.odometry_scale * u.y, 1e-6);
      EXPECT_NEAR(slam::wrapAngle(d.theta - u.theta), 0.0, 1e-6);
      odo_len += std::hypot(u.x, u.y);
      path_len += std::hypot(d.x, d.y);
    }
    EXPECT_GT(odo_len, 2.0);
    EXPECT_NEAR(path_len / odo_len, p.odometry_scale, 1e-6);
  }
  // 40 draws of 1 + N(0, 0.05²): the sample standard deviation lies within ±35 % of 0.05 (p > 0.99).
  EXPECT_GT(stddev(scales), 0.0325);
  EXPECT_LT(stddev(scales), 0.0675);
  // The best particle's scale is also applied to the odometry between processed scans in the trajectory.
  const auto traj = f.trajectory();
  const auto& best = f.bestParticle();
  const auto path = slam::pathOf(best.node);
  std::size_t k = 1;
  while (k + 1 < path.size() && path[k + 1]->scan_index == path[k]->scan_index + 1) ++k;
  ASSERT_LT(k + 1, path.size());  // two processed scans with an unprocessed one between them
  const std::size_t i0 = path[k]->scan_index;
  const auto& oa = log.records[i0].odometry;
  const auto& ob = log.records[i0 + 1].odometry;
  const slam::Pose2 u = slam::relative({oa.x, oa.y, oa.phi}, {ob.x, ob.y, ob.phi});
  const slam::Pose2 d = slam::relative({traj[i0].pose.x, traj[i0].pose.y, traj[i0].pose.phi},
                                       {traj[i0 + 1].pose.x, traj[i0 + 1].pose.y, traj[i0 + 1].pose.phi});
  EXPECT_NEAR(std::hypot(d.x, d.y), best.odometry_scale * std::hypot(u.x, u.y), 1e-6);
}

TEST(OdometryScale, RandomWalkGrowsWithTheDistanceTravelled) {
  const auto log = straightLog();
  slam::RbpfSlam f(deterministicMotion(0.0, 0.02));
  double travelled = 0.0;
  std::size_t last = 0;
  for (std::size_t i = 0; i < log.records.size(); ++i) {
    if (!f.processScan(log.records[i])) continue;
    if (i > 0) {
      const auto& a = log.records[last].odometry;
      const auto& b = log.records[i].odometry;
      travelled += std::hypot(b.x - a.x, b.y - a.y);
    }
    last = i;
  }
  ASSERT_GT(travelled, 2.0);
  std::vector<double> scales;
  for (const auto& p : f.particles()) scales.push_back(p.odometry_scale);
  // Variance 0.02² per metre: standard deviation 0.02·sqrt(travelled) across the 40 particles.
  const double expected = 0.02 * std::sqrt(travelled);
  EXPECT_GT(stddev(scales), 0.65 * expected);
  EXPECT_LT(stddev(scales), 1.35 * expected);
}
