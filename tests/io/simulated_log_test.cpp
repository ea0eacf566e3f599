#include "gridtopo/io/simulated_log.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "gridtopo/io/log_reader.h"
#include "gridtopo/io/rawlog_io.h"
#include "gridtopo/io/scan_conversion.h"

namespace fs = std::filesystem;
using namespace gridtopo::io;

namespace {
double distanceToWalls(double x, double y) {
  double best = 1e9;
  for (const auto& w : simulatedWorld()) {
    const double ex = w[2] - w[0], ey = w[3] - w[1];
    const double t = std::clamp(((x - w[0]) * ex + (y - w[1]) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
    best = std::min(best, std::hypot(x - w[0] - t * ex, y - w[1] - t * ey));
  }
  return best;
}
}  // namespace

TEST(SimulatedLog, RayCastingHitsTheRightWalls) {
  EXPECT_DOUBLE_EQ(castRay(1.0, 1.0, M_PI), 1.0);        // west wall
  EXPECT_DOUBLE_EQ(castRay(1.0, 3.0, 0.0), 1.7);         // pillar at x = 2.7
  EXPECT_NEAR(castRay(6.0, 3.0, M_PI / 2), 3.0, 1e-12);  // north wall
  EXPECT_NEAR(castRay(4.0, 5.7, 0.0), 1.0, 1e-12);       // stub from (5, 5.4) to (5, 6)
  EXPECT_NEAR(castRay(4.0, 5.3, 0.0), 8.0, 1e-12);       // passes under the stub
  EXPECT_NEAR(castRay(6.0, 3.0, M_PI / 4), 3.0 * std::sqrt(2.0), 1e-12);
}

TEST(SimulatedLog, ScansAgreeWithTheGroundTruthAndTheWorld) {
  SimulationOptions o;
  o.range_noise = 0.0;  // centimetre rounding only
  const auto log = simulateLog(o);
  ASSERT_EQ(log.scans.size(), 200u);
  ASSERT_EQ(log.ground_truth.size(), 200u);
  std::size_t valid = 0, no_return = 0;
  double worst = 0;
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const auto& s = log.scans[i].scan;
    const auto& gt = log.ground_truth[i].pose;
    EXPECT_EQ(s.timestamp, log.ground_truth[i].timestamp);
    for (std::size_t k = 0; k < s.size(); ++k) {
      if (!s.valid[k]) {
        EXPECT_TRUE(s.isNoReturn(k));
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
  const auto& a = log.ground_truth.front().pose;
  const auto& b = log.ground_truth.back().pose;
  EXPECT_LT(std::hypot(a.x - b.x, a.y - b.y), 0.2);
  EXPECT_EQ(log.scans.front().odometry.x, a.x);
}

TEST(SimulatedLog, IsDeterministicAndOdometryDrifts) {
  const auto a = simulateLog(), b = simulateLog();
  SimulationOptions other;
  other.seed = 7;
  const auto c = simulateLog(other);
  bool same = true, differs = false;
  for (std::size_t i = 0; i < a.scans.size(); ++i) {
    same = same && a.scans[i].scan.ranges == b.scans[i].scan.ranges && a.scans[i].odometry.x == b.scans[i].odometry.x;
    differs = differs || a.scans[i].scan.ranges != c.scans[i].scan.ranges;
  }
  EXPECT_TRUE(same);
  EXPECT_TRUE(differs);
  const auto& gt = a.ground_truth.back().pose;
  const auto& odo = a.scans.back().odometry;
  const double err = std::hypot(gt.x - odo.x, gt.y - odo.y);
  EXPECT_GT(err, 0.05);  // noticeable drift after a 22 m loop
  EXPECT_LT(err, 3.0);
}

TEST(SimulatedLog, SurvivesARawlogRoundTrip) {
  SimulationOptions o;
  o.scans = 30;
  o.interleave = true;
  const auto log = simulateLog(o);
  const fs::path p = fs::temp_directory_path() / ("gridtopo_sim_" + std::to_string(::getpid()) + ".rawlog");
  RawlogWriteOptions w;
  w.layout = RawlogLayout::ObservationOnly;
  writeRawlog(p.string(), log.scans, w);
  const auto back = readScanLog(p.string());
  fs::remove(p);
  ASSERT_EQ(back.size(), 30u);
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back[i].scan.timestamp, log.scans[i].scan.timestamp);
    EXPECT_EQ(back[i].odometry.x, log.scans[i].odometry.x);
    for (std::size_t k = 0; k < back[i].scan.size(); k += 17) {
      const auto p1 = beamEndpointInRobotFrame(back[i].scan, k), p2 = beamEndpointInRobotFrame(log.scans[i].scan, k);
      EXPECT_NEAR(p1.x, p2.x, 1e-9);
      EXPECT_NEAR(p1.y, p2.y, 1e-9);
    }
  }
}
