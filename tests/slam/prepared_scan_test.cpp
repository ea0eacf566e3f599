// prepareScan's matching end points: surface normals from the neighbouring beams, grazing beams left out of
// matching, the range margin.
#include <gtest/gtest.h>

#include <cmath>

#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/prepared_scan.h"

using namespace gridtopo;
using namespace gridtopo::slam;

namespace {
// A 2 m wide corridor along x (walls y = 0 and y = 2, 60 m long) and a scan from (10, 1) heading east, laser at
// the robot's centre, 181 beams over 180 degrees, max range 12 m, 1 cm range noise.
LaserScan corridorScan(double range_sigma = 0.01) {
  const sim::FloorPlan p = sim::FloorPlan::straightCorridor(60, 2);
  sim::SimOptions so;
  so.max_range = 12;
  so.range_sigma = range_sigma;
  so.sensor_pose = {0, 0, 0};
  return sim::simulatePath(p, {{10, 1, 0}}, {0.0}, so).records.at(0).scan;
}
}  // namespace

TEST(PreparedScan, NormalsOfAWallArePerpendicularToIt) {
  BeamOptions o;
  o.matching_beam_step = 1;
  const PreparedScan p = prepareScan(corridorScan(), o, 0.05);
  ASSERT_GT(p.size(), 150u);
  ASSERT_EQ(p.nx.size(), p.size());
  int with_normal = 0;
  for (std::size_t m = 0; m < p.size(); ++m) {
    if (p.nx[m] == 0.0 && p.ny[m] == 0.0) continue;
    ++with_normal;
    EXPECT_NEAR(std::hypot(p.nx[m], p.ny[m]), 1.0, 1e-12);
    EXPECT_LT(std::abs(p.nx[m]), std::sin(6.0 * M_PI / 180)) << "beam end " << p.ex[m] << ", " << p.ey[m];
  }
  // Every end point has at least two hit neighbours on its wall within ±2 beams: all have a normal.
  EXPECT_EQ(with_normal, static_cast<int>(p.size()));
}

TEST(PreparedScan, NoNormalWhereTheNeighboursAreNotOnOneLine) {
  // A corner: beams 0..4 on a wall x = 3 (from the laser at the origin), beams 5..9 on a wall y = 3.
  LaserScan s;
  s.start_angle = 0.2;
  s.angle_increment = 0.13;
  s.max_range = 30;
  for (int k = 0; k < 10; ++k) {
    const double a = s.start_angle + k * s.angle_increment;
    const double r = std::min(3.0 / std::cos(a), 3.0 / std::sin(a));
    s.ranges.push_back(static_cast<float>(r));
    s.valid.push_back(1);
  }
  BeamOptions o;
  o.matching_beam_step = 1;
  const PreparedScan p = prepareScan(s, o, 0.05);
  ASSERT_EQ(p.size(), 10u);
  int corner_ones = 0;
  for (std::size_t m = 0; m < p.size(); ++m) {
    const bool none = p.nx[m] == 0.0 && p.ny[m] == 0.0;
    const double a = s.start_angle + m * s.angle_increment;
    const bool on_x_wall = std::cos(a) > std::sin(a);
    if (none) {
      ++corner_ones;
      continue;
    }
    // Away from the corner: the wall's own normal.
    if (on_x_wall) EXPECT_NEAR(std::abs(p.nx[m]), 1.0, 1e-6) << m;
    else EXPECT_NEAR(std::abs(p.ny[m]), 1.0, 1e-6) << m;
  }
  EXPECT_GE(corner_ones, 2);  // the beams whose neighbours straddle the corner
  EXPECT_LE(corner_ones, 6);
}

TEST(PreparedScan, GrazingBeamsAreNotMatched) {
  const LaserScan s = corridorScan();
  BeamOptions o;
  o.matching_beam_step = 1;
  const std::size_t all = prepareScan(s, o, 0.05).size();
  o.matching_min_incidence = 20.0 * M_PI / 180;
  const PreparedScan p = prepareScan(s, o, 0.05);
  // The walls are 1 m to the side: a beam meets one at less than 20 degrees beyond 1 / tan(20 deg) = 2.75 m along.
  for (std::size_t m = 0; m < p.size(); ++m) EXPECT_LT(std::abs(p.ex[m]), 1.0 / std::tan(19.0 * M_PI / 180));
  // Beams at 20..160 degrees to the axis (about 141 of the 181) stay, the grazing ones (up to 12 m, about 30) go.
  EXPECT_GT(p.size(), 130u);
  EXPECT_LT(p.size(), all - 20);
  // Every hit is still inserted in the map.
  EXPECT_EQ(p.map_beams.size(), prepareScan(s, BeamOptions{}, 0.05).map_beams.size());
}

TEST(PreparedScan, RangeMarginDropsTheLongestHits) {
  const LaserScan s = corridorScan(0.0);
  BeamOptions o;
  o.matching_beam_step = 1;
  o.matching_range_margin = 2.0;  // the sensor's 12 m: hits at 10 m or more are not matched
  const PreparedScan p = prepareScan(s, o, 0.05);
  for (std::size_t m = 0; m < p.size(); ++m) EXPECT_LT(std::hypot(p.ex[m], p.ey[m]), 10.0);
  o.matching_range_margin = 0.0;
  EXPECT_GT(prepareScan(s, o, 0.05).size(), p.size());
}
