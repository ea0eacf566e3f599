// useMrptScanGeometry (libgridtopo_io_core, no MRPT observations) against MRPT's own round trip
// fromMrptScan(*toMrptScan(scan)): the same bits on every scan of the bundled CARMEN logs and on random scans, so that
// gridtopo-slam reading a CARMEN log without MRPT's observations gives the filter the numbers it gave before.
#include "gridtopo/io/scan_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "gridtopo/io/carmen_log.h"
#include "gridtopo/io/scan_conversion.h"

using namespace gridtopo;
using namespace gridtopo::io;

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every geometry field of `scan` after useMrptScanGeometry equals the MRPT round trip's, bit for bit; the readings
// are untouched. Returns the number of fields that differ (0 = all the same).
int geometryDifferences(const LaserScan& scan) {
  LaserScan ours = scan;
  useMrptScanGeometry(ours);
  const LaserScan mrpt = fromMrptScan(*toMrptScan(scan));
  int differ = 0;
  for (const auto& [a, b] : {std::pair{ours.timestamp, mrpt.timestamp}, std::pair{ours.max_range, mrpt.max_range},
                             std::pair{ours.sensor_pose.x, mrpt.sensor_pose.x},
                             std::pair{ours.sensor_pose.y, mrpt.sensor_pose.y},
                             std::pair{ours.sensor_pose.phi, mrpt.sensor_pose.phi},
                             std::pair{ours.start_angle, mrpt.start_angle},
                             std::pair{ours.angle_increment, mrpt.angle_increment}})
    differ += sameBits(a, b) ? 0 : 1;
  EXPECT_EQ(ours.ranges, scan.ranges);
  EXPECT_EQ(ours.valid, scan.valid);
  return differ;
}

}  // namespace

TEST(ScanGeometry, EqualsMrptsRoundTripOnEveryScanOfTheBundledLogs) {
  std::size_t scans = 0;
  for (const char* log : {"intel", "aces", "mit-csail", "mit-csail-robotlaser", "fr079", "fr-clinic",
                          "freiburg-campus-drift"}) {
    const CarmenLog carmen = readCarmenLog(std::string(GRIDTOPO_DATA_DIR) + "/slam/" + log + ".clf.gz");
    ASSERT_GT(carmen.scans.size(), 1000u) << log;
    int differ = 0;
    for (const ScanRecord& r : carmen.scans) differ += geometryDifferences(r.scan);
    EXPECT_EQ(differ, 0) << log;
    scans += carmen.scans.size();
  }
  EXPECT_GT(scans, 35000u);  // 38 840 scans
}

TEST(ScanGeometry, EqualsMrptsRoundTripOnRandomScans) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int differ = 0;
  for (int i = 0; i < 20000; ++i) {
    LaserScan s;
    const std::size_t n = std::vector<std::size_t>{2, 3, 180, 181, 360, 361, 541, 683, 1081}[i % 9];
    // Round degree steps (the usual lasers) and arbitrary ones, either direction.
    const double inc_deg = (i % 3 == 0) ? (unit(rng) * 2.0) : std::vector<double>{1.0, 0.5, 0.25, 0.36, 360.0 / 1024}[i % 5];
    s.angle_increment = ((i % 4 == 1) ? -1.0 : 1.0) * inc_deg * M_PI / 180.0;
    s.start_angle = (unit(rng) - 0.5) * 2.0 * M_PI * ((i % 7 == 0) ? 3.0 : 1.0);
    s.sensor_pose = {(unit(rng) - 0.5) * 0.6, (unit(rng) - 0.5) * 0.6, (unit(rng) - 0.5) * ((i % 5 == 0) ? 20.0 : 6.3)};
    s.max_range = (i % 2 == 0) ? 81.9 : 1.0 + 80.0 * unit(rng);
    s.timestamp = (i % 2 == 0) ? 976052857.0 + 1e4 * unit(rng) : 100.0 * unit(rng);
    s.ranges.assign(n, 1.5f);
    s.valid.assign(n, 1);
    differ += geometryDifferences(s);
  }
  EXPECT_EQ(differ, 0);
}

TEST(ScanGeometry, AScanMrptCannotHoldIsLeftAsItIs) {
  LaserScan s;
  s.ranges = {1.0f};
  s.valid = {1};
  s.start_angle = 0.3;
  s.angle_increment = 0.01;
  s.timestamp = 12.345678912;
  ASSERT_NE(whyMrptScanCannotHold(s), nullptr);
  useMrptScanGeometry(s);
  EXPECT_EQ(s.start_angle, 0.3);
  EXPECT_EQ(s.timestamp, 12.345678912);
}
