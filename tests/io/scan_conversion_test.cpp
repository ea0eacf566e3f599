#include "gridtopo/io/scan_conversion.h"

#include <gtest/gtest.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>
#include <limits>
#include <tuple>

using namespace gridtopo;
using namespace gridtopo::io;

namespace {
constexpr double kDeg = M_PI / 180.0;

LaserScan makeScan(std::size_t n, double start_deg, double inc_deg, mrpt::math::TPose2D mount = {0, 0, 0}) {
  LaserScan s;
  s.timestamp = 976052857.337284;
  s.start_angle = start_deg * kDeg;
  s.angle_increment = inc_deg * kDeg;
  s.max_range = 81.9;
  s.sensor_pose = mount;
  for (std::size_t k = 0; k < n; ++k) {
    // Distinct ranges, a few far ones, so a wrong angle or order shows up in the end points.
    s.ranges.push_back(static_cast<float>(1.0 + 0.37 * static_cast<double>(k % 23) + (k % 41 == 0 ? 60.0 : 0.0)));
    s.valid.push_back(1);
  }
  return s;
}

// Largest distance between corresponding beam end points (robot frame) of two scans.
double maxEndpointError(const LaserScan& a, const LaserScan& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const auto pa = beamEndpointInRobotFrame(a, k), pb = beamEndpointInRobotFrame(b, k);
    worst = std::max(worst, std::hypot(pa.x - pb.x, pa.y - pb.y));
  }
  return worst;
}

// MRPT's own projection of a scan's valid beams into the robot frame, compared with ours.
double maxErrorAgainstMrpt(const LaserScan& s, const mrpt::obs::CObservation2DRangeScan& obs) {
  mrpt::maps::CSimplePointsMap pts;
  pts.insertionOptions.minDistBetweenLaserPoints = 0;
  pts.insertObservation(obs);
  std::size_t j = 0;
  double worst = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (!s.valid[k]) continue;
    EXPECT_LT(j, pts.size());
    if (j >= pts.size()) break;
    float x, y, z;
    pts.getPoint(j++, x, y, z);
    const auto p = beamEndpointInRobotFrame(s, k);
    worst = std::max(worst, std::hypot(p.x - x, p.y - y));
  }
  EXPECT_EQ(j, pts.size());
  return worst;
}
}  // namespace

TEST(ScanConversion, Carmen180BeamScanIsWrittenWithTheRightGeometry) {
  // CARMEN FLASER: 180 beams from -90 deg to +89 deg, 1 deg apart: not symmetric about the laser's x axis.
  const LaserScan s = makeScan(180, -90.0, 1.0, {0.0, 0.0, 0.0});
  const auto obs = toMrptScan(s);
  EXPECT_FLOAT_EQ(obs->aperture, static_cast<float>(179.0 * kDeg));
  EXPECT_TRUE(obs->rightToLeft);
  EXPECT_FLOAT_EQ(obs->maxRange, 81.9f);
  EXPECT_NEAR(obs->sensorPose.yaw(), -0.5 * kDeg, 1e-15);
  EXPECT_EQ(obs->sensorPose.x(), 0.0);
  EXPECT_EQ(obs->sensorLabel, "LASER");
  ASSERT_EQ(obs->getScanSize(), 180u);
  // First beam at -90 deg, last at +89 deg in the robot frame (MRPT computes angles in float).
  EXPECT_NEAR(obs->sensorPose.yaw() + obs->getScanAngle(0), -90.0 * kDeg, 2e-7);
  EXPECT_NEAR(obs->sensorPose.yaw() + obs->getScanAngle(179), 89.0 * kDeg, 2e-7);
  // MRPT's own projection lands on our end points (float precision, ranges up to 64 m).
  EXPECT_LT(maxErrorAgainstMrpt(s, *obs), 5e-5);
}

TEST(ScanConversion, RoundTripKeepsEveryBeamEndpointInTheRobotFrame) {
  struct Case {
    const char* name;
    std::size_t n;
    double start, inc;
    mrpt::math::TPose2D mount;
  };
  const Case cases[] = {
      {"carmen180", 180, -90.0, 1.0, {0, 0, 0}},
      {"interleaved180", 180, -89.5, 1.0, {0, 0, 0}},
      {"sick181", 181, -90.0, 1.0, {0.25, 0.0, 0.0}},
      {"sick361", 361, -90.0, 0.5, {0.1, -0.05, 0.02}},
      {"sick360", 360, -90.0, 0.5, {0, 0, 0}},
      {"quarter", 721, -90.0, 0.25, {0, 0, 0}},
      {"hokuyo", 682, -119.8828125, 360.0 / 1024.0, {0.3, 0.1, M_PI / 2}},
      {"left-to-right", 180, 90.0, -1.0, {0, 0, 0}},
      {"rear-laser", 180, -90.0, 1.0, {-0.2, 0.0, M_PI}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const LaserScan in = makeScan(c.n, c.start, c.inc, c.mount);
    const auto obs = toMrptScan(in);
    EXPECT_EQ(obs->rightToLeft, c.inc > 0);
    EXPECT_LT(maxErrorAgainstMrpt(in, *obs), 1e-4);
    const LaserScan out = fromMrptScan(*obs);
    ASSERT_EQ(out.size(), in.size());
    EXPECT_LT(maxEndpointError(in, out), 1e-9);
    EXPECT_EQ(out.timestamp, in.timestamp);
    EXPECT_FLOAT_EQ(static_cast<float>(out.max_range), 81.9f);
    for (std::size_t k = 0; k < in.size(); ++k) EXPECT_EQ(out.ranges[k], in.ranges[k]);
    EXPECT_NEAR(std::abs(out.angle_increment), std::abs(c.inc) * kDeg, 1e-15);
  }
}

TEST(ScanConversion, ArbitraryIncrementRoundTripsToFloatPrecision) {
  // 0.0123456789 rad is no whole number of 1e-7 deg: MRPT's float aperture limits the precision.
  LaserScan in = makeScan(200, -70.0, 0.0123456789 / kDeg);
  const LaserScan out = fromMrptScan(*toMrptScan(in));
  const double err = maxEndpointError(in, out);
  EXPECT_LT(err, 2e-5);  // ranges up to 64 m, angle error ~1e-7 rad
}

TEST(ScanConversion, UpsideDownLaserFromMrptKeepsBeamDirections) {
  // An MRPT scan from a laser mounted upside down (roll = 180 deg): its beams sweep clockwise on the robot.
  auto obs = mrpt::obs::CObservation2DRangeScan::Create();
  obs->aperture = static_cast<float>(M_PI);
  obs->rightToLeft = true;
  obs->maxRange = 30.0f;
  obs->sensorPose = mrpt::poses::CPose3D(0.2, 0.1, 0.3, 0.3, 0.0, M_PI);
  obs->resizeScan(181);
  for (std::size_t k = 0; k < 181; ++k) {
    obs->setScanRange(k, static_cast<float>(2.0 + 0.01 * static_cast<double>(k)));
    obs->setScanRangeValidity(k, true);
  }
  const LaserScan s = fromMrptScan(*obs);
  EXPECT_LT(s.angle_increment, 0.0);
  EXPECT_LT(maxErrorAgainstMrpt(s, *obs), 1e-5);
}

TEST(ScanConversion, NoReturnReadingsStayInTheScanAsInvalid) {
  LaserScan s = makeScan(180, -90.0, 1.0);
  s.max_range = 50.0;
  s.ranges[3] = 81.91f;  // CARMEN "no return": beyond max range
  s.valid[3] = 0;
  s.ranges[4] = std::numeric_limits<float>::infinity();
  s.valid[4] = 0;
  s.ranges[5] = std::numeric_limits<float>::quiet_NaN();
  s.valid[5] = 0;
  s.ranges[6] = -1.0f;
  s.valid[6] = 1;  // a negative range is never valid
  const auto obs = toMrptScan(s);
  EXPECT_EQ(obs->getScanRange(3), 81.91f);
  EXPECT_FALSE(obs->getScanRangeValidity(3));
  EXPECT_EQ(obs->getScanRange(4), 50.0f);
  EXPECT_FALSE(obs->getScanRangeValidity(4));
  EXPECT_EQ(obs->getScanRange(5), 0.0f);
  EXPECT_FALSE(obs->getScanRangeValidity(5));
  EXPECT_FALSE(obs->getScanRangeValidity(6));
  EXPECT_TRUE(obs->getScanRangeValidity(7));
  const LaserScan back = fromMrptScan(*obs);
  EXPECT_TRUE(back.isNoReturn(3));
  EXPECT_TRUE(back.isNoReturn(4));
  EXPECT_FALSE(back.isNoReturn(5));
  EXPECT_EQ(back.valid[7], 1);
}

TEST(ScanConversion, TimestampsKeepMicrosecondsExactly) {
  for (const double t : {1002560357.218569, 976052857.337284, 976052858.404130, 70.2899, 0.0, 1365.5, 1e-6}) {
    SCOPED_TRACE(t);
    EXPECT_EQ(fromMrptTime(toMrptTime(t)), t);
  }
  // Finer than MRPT's 100 ns tick: rounded to the nearest tick.
  EXPECT_NEAR(fromMrptTime(toMrptTime(12.34567891234)), 12.3456789, 1e-12);
  // Same instant as MRPT's own conversion (which truncates) to within one tick.
  const double t = 1002560357.218569;
  const auto a = toMrptTime(t).time_since_epoch().count();
  const auto b = mrpt::Clock::fromDouble(t).time_since_epoch().count();
  EXPECT_LE(std::llabs(a - b), 1);
  EXPECT_NEAR(mrpt::Clock::toDouble(toMrptTime(t)), t, 2e-7);
  EXPECT_THROW(toMrptTime(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

TEST(ScanConversion, MrptGeometryKeepsTheBeamsAndMakesTheRoundTripExact) {
  for (const auto& [n, start, inc] : {std::tuple<std::size_t, double, double>{180, -90, 1}, {361, -90, 0.5},
                                      {181, 90, -1}, {1081, -135, 0.25}, {682, -119.8828, 0.3515625}}) {
    SCOPED_TRACE(n);
    const LaserScan raw = makeScan(n, start, inc, {0.12, -0.03, 0.4});
    LaserScan s = raw;
    useMrptScanGeometry(s);
    EXPECT_LT(maxEndpointError(raw, s), 1e-9);
    EXPECT_EQ(s.ranges, raw.ranges);
    EXPECT_EQ(s.valid, raw.valid);
    const LaserScan back = fromMrptScan(*toMrptScan(s));
    EXPECT_EQ(back.start_angle, s.start_angle);
    EXPECT_EQ(back.angle_increment, s.angle_increment);
    EXPECT_EQ(back.sensor_pose.phi, s.sensor_pose.phi);
    EXPECT_EQ(back.max_range, s.max_range);
    EXPECT_EQ(back.timestamp, s.timestamp);
    LaserScan again = s;  // idempotent
    useMrptScanGeometry(again);
    EXPECT_EQ(again.start_angle, s.start_angle);
    EXPECT_EQ(again.sensor_pose.phi, s.sensor_pose.phi);
  }
  // A scan MRPT cannot hold is left as it is.
  LaserScan one = makeScan(1, 0, 1);
  useMrptScanGeometry(one);
  EXPECT_EQ(one.start_angle, 0.0);
}

TEST(ScanConversion, RejectsScansMrptCannotHold) {
  EXPECT_THROW(toMrptScan(makeScan(1, 0.0, 1.0)), std::invalid_argument);
  EXPECT_THROW(toMrptScan(makeScan(180, -90.0, 0.0)), std::invalid_argument);
  LaserScan s = makeScan(10, 0.0, 1.0);
  s.valid.pop_back();
  EXPECT_THROW(toMrptScan(s), std::invalid_argument);
  s = makeScan(10, 0.0, 1.0);
  s.max_range = 0;
  EXPECT_THROW(toMrptScan(s), std::invalid_argument);
  s = makeScan(10, 0.0, 1.0);
  s.sensor_pose.phi = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(toMrptScan(s), std::invalid_argument);
  s = makeScan(10, 0.0, 1.0);
  s.timestamp = std::numeric_limits<double>::infinity();
  EXPECT_THROW(toMrptScan(s), std::invalid_argument);
}
