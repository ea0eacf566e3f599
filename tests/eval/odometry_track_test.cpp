// OdometryTrack and its helpers on hand-made readings: nearest-in-time ties, stable sorting, interpolation along
// the shorter arc and clamping, and which readings of a CARMEN log each source picks.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "gridtopo/eval/odometry_track.h"
#include "gridtopo/io/carmen_log.h"

using namespace gridtopo::eval;
using gridtopo::TimedPose;
using mrpt::math::TPose2D;

namespace {
/// Readings told apart by their x.
TimedPose at(double t, double x, double y = 0, double phi = 0) { return {t, TPose2D{x, y, phi}}; }

std::vector<double> xs(const std::vector<TimedPose>& v) {
  std::vector<double> out;
  for (const auto& p : v) out.push_back(p.pose.x);
  return out;
}
}  // namespace

TEST(OdometryTrack, SourceNamesRoundTripAndBadNamesThrow) {
  for (auto s : {OdometrySource::Auto, OdometrySource::OdomLines, OdometrySource::LaserLines})
    EXPECT_EQ(odometrySourceFromString(toString(s)), s);
  EXPECT_STREQ(toString(OdometrySource::Auto), "auto");
  EXPECT_STREQ(toString(OdometrySource::OdomLines), "odom");
  EXPECT_STREQ(toString(OdometrySource::LaserLines), "laser");
  for (const std::string bad : {"", "ODOM", "odometry", " auto"}) {
    try {
      odometrySourceFromString(bad);
      FAIL() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), "odometry source must be auto, odom or laser (got '" + bad + "')");
    }
  }
}

TEST(OdometryTrack, NearestInTimeTiesGoToTheEarlierAndTheFirstOfEqualTimestamps) {
  const std::vector<TimedPose> s = {at(1.0, 1), at(2.0, 2), at(2.0, 3), at(4.0, 4)};
  EXPECT_EQ(nearestInTime(s, -5.0).pose.x, 1);  // before the first
  EXPECT_EQ(nearestInTime(s, 1.0).pose.x, 1);
  EXPECT_EQ(nearestInTime(s, 1.4).pose.x, 1);
  EXPECT_EQ(nearestInTime(s, 1.5).pose.x, 1);   // tie 1.0 / 2.0: the earlier
  EXPECT_EQ(nearestInTime(s, 1.6).pose.x, 2);   // first of the two at 2.0
  EXPECT_EQ(nearestInTime(s, 2.0).pose.x, 2);
  EXPECT_EQ(nearestInTime(s, 2.5).pose.x, 2);   // after the equal pair: still the first of them
  EXPECT_EQ(nearestInTime(s, 3.0).pose.x, 2);   // tie 2.0 / 4.0: the earlier, first of its equals
  EXPECT_EQ(nearestInTime(s, 3.01).pose.x, 4);
  EXPECT_EQ(nearestInTime(s, 1e9).pose.x, 4);   // after the last
  EXPECT_EQ(&nearestInTime(s, 4.0), &s[3]);     // a reference into the sequence
  EXPECT_THROW(nearestInTime({}, 1.0), std::logic_error);
}

TEST(OdometryTrack, SortByTimeIsStable) {
  std::vector<TimedPose> v = {at(3.0, 1), at(1.0, 2), at(3.0, 3), at(2.0, 4), at(1.0, 5)};
  sortByTime(v);
  EXPECT_EQ(xs(v), (std::vector<double>{2, 5, 4, 1, 3}));
}

TEST(OdometryTrack, ConstructorSortsStablyAndEmptyTracksThrow) {
  const OdometryTrack t({at(5.0, 1), at(0.0, 2), at(5.0, 3)});
  EXPECT_FALSE(t.empty());
  EXPECT_EQ(t.size(), 3u);
  EXPECT_EQ(xs(t.poses()), (std::vector<double>{2, 1, 3}));
  EXPECT_EQ(t.nearest(4.0).pose.x, 1);

  const OdometryTrack e;
  EXPECT_TRUE(e.empty());
  EXPECT_EQ(e.size(), 0u);
  EXPECT_THROW(e.nearest(0.0), std::logic_error);
  EXPECT_THROW(e.interpolate(0.0), std::logic_error);
  EXPECT_THROW(e.at(0.0, true), std::logic_error);
  EXPECT_THROW(e.at(0.0, false), std::logic_error);
}

TEST(OdometryTrack, InterpolatesLinearlyAndClampsOutsideTheSpan) {
  const OdometryTrack t({at(10.0, 0, 0, 0), at(12.0, 2, 4, 0.2), at(13.0, 2, 5, 0.2)});
  const TPose2D p = t.interpolate(10.5);
  EXPECT_DOUBLE_EQ(p.x, 0.5);
  EXPECT_DOUBLE_EQ(p.y, 1.0);
  EXPECT_NEAR(p.phi, 0.05, 1e-12);  // through wrapToPi: not bit-exact
  const TPose2D q = t.interpolate(12.5);  // second interval
  EXPECT_DOUBLE_EQ(q.x, 2.0);
  EXPECT_DOUBLE_EQ(q.y, 4.5);
  EXPECT_NEAR(q.phi, 0.2, 1e-12);
  // Exactly at a reading: that reading.
  EXPECT_DOUBLE_EQ(t.interpolate(12.0).y, 4.0);
  EXPECT_DOUBLE_EQ(t.interpolate(10.0).y, 0.0);
  // Clamped to the first / last reading.
  EXPECT_DOUBLE_EQ(t.interpolate(-100.0).x, 0.0);
  EXPECT_DOUBLE_EQ(t.interpolate(-100.0).y, 0.0);
  EXPECT_DOUBLE_EQ(t.interpolate(100.0).y, 5.0);
  EXPECT_DOUBLE_EQ(t.interpolate(100.0).phi, 0.2);  // the reading itself
}

TEST(OdometryTrack, HeadingTakesTheShorterArcAcrossPi) {
  // 3.0 rad to -3.0 rad: the shorter way is +0.2832 rad through π, not -6 rad through 0.
  const OdometryTrack t({at(0.0, 0, 0, 3.0), at(4.0, 0, 0, -3.0)});
  const double d = 2 * M_PI - 6.0;
  EXPECT_NEAR(t.interpolate(1.0).phi, 3.0 + 0.25 * d, 1e-12);
  EXPECT_NEAR(t.interpolate(3.0).phi, 3.0 + 0.75 * d - 2 * M_PI, 1e-12);  // past π: wrapped to (-π, π]
  EXPECT_LT(t.interpolate(3.0).phi, -3.0);
}

TEST(OdometryTrack, InterpolationAfterEqualTimestampsStartsFromTheLastOfThem) {
  const OdometryTrack t({at(0.0, 0), at(1.0, 1), at(1.0, 5), at(2.0, 7)});
  EXPECT_DOUBLE_EQ(t.interpolate(0.5).x, 0.5);
  EXPECT_DOUBLE_EQ(t.interpolate(1.0).x, 1.0);  // the first reading at 1.0
  EXPECT_DOUBLE_EQ(t.interpolate(1.5).x, 6.0);  // between the last reading at 1.0 (x 5) and x 7
}

TEST(OdometryTrack, AtIsNearestOrInterpolated) {
  const OdometryTrack t({at(0.0, 0, 0), at(1.0, 10, 20)});
  EXPECT_DOUBLE_EQ(t.at(0.3, false).x, 0.0);
  EXPECT_DOUBLE_EQ(t.at(0.7, false).x, 10.0);
  EXPECT_DOUBLE_EQ(t.at(0.5, false).x, 0.0);  // tie: the earlier
  EXPECT_DOUBLE_EQ(t.at(0.3, true).x, 3.0);
  EXPECT_DOUBLE_EQ(t.at(0.3, true).y, 6.0);
}

namespace {
gridtopo::io::CarmenLog logWith(bool odom_lines) {
  gridtopo::io::CarmenLog log;
  if (odom_lines) {
    // File order need not be time order.
    for (double t : {2.0, 1.0}) {
      gridtopo::OdometryReading o;
      o.timestamp = t;
      o.pose = {100 + t, 0, 0};
      log.odometry.push_back(o);
    }
  }
  for (int k = 0; k < 3; ++k) {
    gridtopo::ScanRecord s;
    s.scan.timestamp = 10.0 - k;  // 10, 9, 8
    s.has_odometry = k != 1;      // the scan at 9 carries no odometry
    s.odometry = {static_cast<double>(k), 0, 0};
    log.scans.push_back(s);
  }
  return log;
}
}  // namespace

TEST(OdometryTrack, FromScansPicksOdomReadingsOrTheScansOdometry) {
  OdometrySource used = OdometrySource::Auto;
  // Any log reader's output: the scan records and the odometry readings (here a CARMEN log's).
  const auto with_odom = logWith(true), without_odom = logWith(false);
  // Auto with ODOM lines: the ODOM lines, sorted by time.
  auto t = OdometryTrack::fromScans(with_odom.scans, with_odom.odometry, OdometrySource::Auto, &used);
  EXPECT_EQ(used, OdometrySource::OdomLines);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses()[0].timestamp, 1.0);
  EXPECT_EQ(t.poses()[0].pose.x, 101.0);
  EXPECT_EQ(t.poses()[1].pose.x, 102.0);

  // Auto without ODOM lines: the laser lines that carry odometry, sorted by time.
  t = OdometryTrack::fromScans(without_odom.scans, without_odom.odometry, OdometrySource::Auto, &used);
  EXPECT_EQ(used, OdometrySource::LaserLines);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses()[0].timestamp, 8.0);
  EXPECT_EQ(t.poses()[0].pose.x, 2.0);
  EXPECT_EQ(t.poses()[1].timestamp, 10.0);
  EXPECT_EQ(t.poses()[1].pose.x, 0.0);

  // Explicit choices are obeyed even when the other source exists or this one is empty.
  t = OdometryTrack::fromScans(with_odom.scans, with_odom.odometry, OdometrySource::LaserLines, &used);
  EXPECT_EQ(used, OdometrySource::LaserLines);
  EXPECT_EQ(t.size(), 2u);
  t = OdometryTrack::fromScans(without_odom.scans, without_odom.odometry, OdometrySource::OdomLines, &used);
  EXPECT_EQ(used, OdometrySource::OdomLines);
  EXPECT_TRUE(t.empty());
  // `used` is optional.
  EXPECT_EQ(OdometryTrack::fromScans(with_odom.scans, with_odom.odometry, OdometrySource::Auto).size(), 2u);
}
