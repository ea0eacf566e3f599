#include "gridtopo/sim/simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "gridtopo/io/log_reader.h"
#include "gridtopo/io/rawlog_io.h"
#include "gridtopo/io/scan_conversion.h"

namespace fs = std::filesystem;
using namespace gridtopo::io;
using namespace gridtopo::sim;

namespace {
double distanceToWalls(double x, double y) {
  double best = 1e9;
  for (const auto& w : FloorPlan::pillarRoom().walls) {
    const double ex = w.x1 - w.x0, ey = w.y1 - w.y0;
    const double t = std::clamp(((x - w.x0) * ex + (y - w.y0) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
    best = std::min(best, std::hypot(x - w.x0 - t * ex, y - w.y0 - t * ey));
  }
  return best;
}
}  // namespace

TEST(SimulatedLog, RayCastingHitsTheRightWalls) {
  const auto room = FloorPlan::pillarRoom();
  auto castRay = [&](double x, double y, double a) { return room.rayCast(x, y, a); };
  EXPECT_DOUBLE_EQ(castRay(1.0, 1.0, M_PI), 1.0);        // west wall
  EXPECT_DOUBLE_EQ(castRay(1.0, 3.0, 0.0), 1.7);         // pillar at x = 2.7
  EXPECT_NEAR(castRay(6.0, 3.0, M_PI / 2), 3.0, 1e-12);  // north wall
  EXPECT_NEAR(castRay(4.0, 5.7, 0.0), 1.0, 1e-12);       // stub from (5, 5.4) to (5, 6)
  EXPECT_NEAR(castRay(4.0, 5.3, 0.0), 8.0, 1e-12);       // passes under the stub
  EXPECT_NEAR(castRay(6.0, 3.0, M_PI / 4), 3.0 * std::sqrt(2.0), 1e-12);
}

TEST(SimulatedLog, ScansAgreeWithTheGroundTruthAndTheWorld) {
  SimOptions o = pillarRoomOptions();
  o.range_sigma = 0.0;  // centimetre rounding only
  const auto log = simulatePillarRoom(200, o);
  const auto truth = log.timedTruth();
  ASSERT_EQ(log.records.size(), 200u);
  ASSERT_EQ(truth.size(), 200u);
  std::size_t valid = 0, no_return = 0;
  double worst = 0;
  for (std::size_t i = 0; i < log.records.size(); ++i) {
    const auto& s = log.records[i].scan;
    EXPECT_EQ(s.size(), 180u);
    EXPECT_NEAR(s.angle_increment, M_PI / 180, 1e-12);
    const auto& gt = truth[i].pose;
    EXPECT_EQ(s.timestamp, truth[i].timestamp);
    for (std::size_t k = 0; k < s.size(); ++k) {
      if (!s.valid[k]) {
        EXPECT_TRUE(s.isNoReturn(k));
        EXPECT_EQ(s.ranges[k], 9.0f);
        ++no_return;
        continue;
      }
      ++valid;
      const auto p = beamEndpointInRobotFrame(s, k);
      const double x = gt.x + std::cos(gt.phi) * p.x - std::sin(gt.phi) * p.y;
      const double y = gt.y + std::sin(gt.phi) * p.x + std::cos(gt.phi) * p.y;
      worst = std::max(worst, distanceToWalls(x, y));
    }
  }
  EXPECT_LT(worst, 0.0051);  // every return lies on a wall, up to the centimetre rounding
  EXPECT_GT(no_return, 1000u);
  EXPECT_GT(valid, 30000u);
  // One loop: the last pose is one step short of the first.
  const auto& a = truth.front().pose;
  const auto& b = truth.back().pose;
  EXPECT_LT(std::hypot(a.x - b.x, a.y - b.y), 0.2);
  EXPECT_EQ(log.records.front().odometry.x, a.x);
}

TEST(SimulatedLog, IsDeterministicAndOdometryDrifts) {
  const auto a = simulatePillarRoom(), b = simulatePillarRoom();
  SimOptions other = pillarRoomOptions();
  other.seed = 7;
  const auto c = simulatePillarRoom(200, other);
  bool same = true, differs = false;
  for (std::size_t i = 0; i < a.records.size(); ++i) {
    same = same && a.records[i].scan.ranges == b.records[i].scan.ranges &&
           a.records[i].odometry.x == b.records[i].odometry.x;
    differs = differs || a.records[i].scan.ranges != c.records[i].scan.ranges;
  }
  EXPECT_TRUE(same);
  EXPECT_TRUE(differs);
  const auto& gt = a.truth.back();
  const auto& odo = a.records.back().odometry;
  const double err = std::hypot(gt.x - odo.x, gt.y - odo.y);
  EXPECT_GT(err, 0.05);  // noticeable drift after a 22 m loop
  EXPECT_LT(err, 3.0);
}

TEST(SimulatedLog, SurvivesARawlogRoundTrip) {
  SimOptions o = pillarRoomOptions();
  o.interleave = true;
  const auto sim = simulatePillarRoom(30, o);
  const auto& log = sim.records;
  EXPECT_NEAR(log[1].scan.start_angle - log[0].scan.start_angle, 0.5 * M_PI / 180, 1e-12);
  const fs::path p = fs::temp_directory_path() / ("gridtopo_sim_" + std::to_string(::getpid()) + ".rawlog");
  RawlogWriteOptions w;
  w.layout = RawlogLayout::ObservationOnly;
  writeRawlog(p.string(), log, w);
  const auto back = readScanLog(p.string());
  fs::remove(p);
  ASSERT_EQ(back.size(), 30u);
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back[i].scan.timestamp, log[i].scan.timestamp);
    EXPECT_EQ(back[i].odometry.x, log[i].odometry.x);
    for (std::size_t k = 0; k < back[i].scan.size(); k += 17) {
      const auto p1 = beamEndpointInRobotFrame(back[i].scan, k), p2 = beamEndpointInRobotFrame(log[i].scan, k);
      EXPECT_NEAR(p1.x, p2.x, 1e-9);
      EXPECT_NEAR(p1.y, p2.y, 1e-9);
    }
  }
}

TEST(Simulator, WaypointDrivingFollowsTheWaypointsAndTheOfficeLoopCloses) {
  SimOptions o;
  const auto log = simulate(FloorPlan::officeLoop(), officeLoopWaypoints(1), o);
  ASSERT_GT(log.records.size(), 500u);
  ASSERT_EQ(log.truth.size(), log.records.size());
  // Consecutive true poses are at most scan_spacing apart (m or rad) and timestamps increase with the motion.
  for (std::size_t i = 1; i < log.truth.size(); ++i) {
    const double d = std::hypot(log.truth[i].x - log.truth[i - 1].x, log.truth[i].y - log.truth[i - 1].y);
    const double a = std::abs(std::remainder(log.truth[i].phi - log.truth[i - 1].phi, 2 * M_PI));
    EXPECT_LE(d, o.scan_spacing + 1e-9);
    EXPECT_LE(a, o.scan_spacing + 1e-9);
    EXPECT_NEAR(log.records[i].scan.timestamp - log.records[i - 1].scan.timestamp, (d + 0.5 * a) / o.speed, 1e-9);
  }
  const auto& last = log.truth.back();
  EXPECT_NEAR(last.x, 10.0, 1e-6);  // the final waypoint
  EXPECT_NEAR(last.y, 2.8, 1e-6);
  // The heading bias makes odometry drift: after the ~50 m loop it is off by metres, not centimetres.
  const double drift = std::hypot(log.records.back().odometry.x - last.x, log.records.back().odometry.y - last.y);
  EXPECT_GT(drift, 0.5);
  // Without bias and noise the odometry is the ground truth up to rounding.
  SimOptions exact = o;
  exact.odo_sigma_xy = exact.odo_sigma_theta = exact.odo_sigma_theta_per_m = exact.odo_drift_theta = 0;
  const auto clean = simulate(FloorPlan::officeLoop(), officeLoopWaypoints(1), exact);
  EXPECT_NEAR(clean.records.back().odometry.x, clean.truth.back().x, 1e-9);
  EXPECT_NEAR(clean.records.back().odometry.y, clean.truth.back().y, 1e-9);
}

TEST(Simulator, NoReturnBeamsAndBadOptions) {
  SimOptions o;
  o.max_range = 3.0;  // most of the office is farther away
  const auto log = simulate(FloorPlan::officeLoop(), {{10, 2, 0}}, o);
  ASSERT_EQ(log.records.size(), 1u);
  const auto& s = log.records[0].scan;
  std::size_t none = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (s.valid[k]) {
      EXPECT_LT(s.ranges[k], 3.0f);
    } else {
      EXPECT_EQ(s.ranges[k], 3.0f);  // no_return_range 0: reported at max range
      ++none;
    }
  }
  EXPECT_GT(none, 20u);
  EXPECT_LT(none, s.size());
  SimOptions bad = o;
  bad.beams = 1;
  EXPECT_THROW(simulate(FloorPlan::officeLoop(), {{10, 2, 0}}, bad), std::invalid_argument);
  EXPECT_THROW(simulatePath(FloorPlan::officeLoop(), {{10, 2, 0}}, {}, o), std::invalid_argument);
  EXPECT_THROW(simulatePillarRoom(1), std::invalid_argument);
}
