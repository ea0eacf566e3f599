#include "test_tmp_dir.h"
#include "gridtopo/io/log_reader.h"

#include <gtest/gtest.h>
#include <mrpt/poses/CPose2D.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/io/rawlog_io.h"
#include "gridtopo/io/scan_conversion.h"
#include "synthetic_scans.h"

namespace fs = std::filesystem;
using namespace gridtopo;
using namespace gridtopo::io;

using gridtopo::test::tmpDir;
using gridtopo::test::readText;

namespace {
const std::string kIntel = std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.clf.gz";
const std::string kAces = std::string(GRIDTOPO_DATA_DIR) + "/slam/aces.clf.gz";

double maxEndpointError(const LaserScan& a, const LaserScan& b) {
  double worst = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const auto pa = beamEndpointInRobotFrame(a, k), pb = beamEndpointInRobotFrame(b, k);
    worst = std::max(worst, std::hypot(pa.x - pb.x, pa.y - pb.y));
  }
  return worst;
}

// Intel is read once for all the tests of this file (about a second).
const std::vector<ScanRecord>& intel() {
  static const std::vector<ScanRecord> scans = readScanLog(kIntel);
  return scans;
}
}  // namespace

TEST(LogReader, ReadsIntelCarmenLog) {
  ScanLogInfo info;
  const auto& scans = intel();
  EXPECT_EQ(detectLogFormat(kIntel), LogFormat::Carmen);
  ASSERT_EQ(scans.size(), 13631u);
  EXPECT_EQ(scans.front().scan.timestamp, 976052857.337530);
  EXPECT_EQ(scans.back().scan.timestamp, 976055548.624744);
  EXPECT_EQ(scans.front().scan.size(), 180u);
  EXPECT_TRUE(scans.front().has_odometry);
  std::size_t backwards = 0;
  for (std::size_t i = 1; i < scans.size(); ++i) backwards += scans[i].scan.timestamp < scans[i - 1].scan.timestamp;
  EXPECT_EQ(backwards, 631u);
}

TEST(LogReader, OdomLinesAreInterpolatedAtTheScanTime) {
  LogReadOptions opt;
  opt.odometry = OdometrySource::OdomLines;
  ScanLogInfo info;
  const auto scans = readScanLog(kIntel, opt, info);
  ASSERT_EQ(scans.size(), 13631u);
  EXPECT_EQ(info.odometry_messages, 26915u);
  // Intel's ODOM lines span 976052857.337284 .. 976055548.625127; one scan (976055548.633890, logged before
  // the last one in file order) is later than all of them and keeps its laser-line odometry.
  EXPECT_EQ(info.odometry_fallbacks, 1u);
  // The robot stands still at the start: ODOM 0 0 -0.002458 on both sides of the first scan.
  EXPECT_EQ(scans.front().odometry.x, 0.0);
  EXPECT_NEAR(scans.front().odometry.phi, -0.002458, 1e-12);
  // ODOM and laser-line odometry are the same frame and mostly agree to millimetres; where ODOM timestamps
  // step backwards they differ by up to 0.76 m (figures cross-checked with an independent Python script).
  const auto& laser = intel();
  double worst = 0;
  std::size_t above_10cm = 0;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const double d = std::hypot(scans[i].odometry.x - laser[i].odometry.x, scans[i].odometry.y - laser[i].odometry.y);
    worst = std::max(worst, d);
    above_10cm += d > 0.1;
  }
  EXPECT_NEAR(worst, 0.761518, 1e-5);
  EXPECT_EQ(above_10cm, 272u);
}

TEST(LogReader, OdomInterpolationOnASmallLog) {
  // ODOM at t = 1 and t = 3 (logged in reverse order); scans at 0.5 (before: fallback), 2 (between), 3 (exact)
  // and 4 (after: fallback).
  const fs::path p = tmpDir() / "odom.log";
  std::ofstream(p) << "ODOM 3.0 2.0 0.5 0 0 0 3.0 host 3.0\n"
                   << "ODOM 1.0 0.0 0.1 0 0 0 1.0 host 1.0\n"
                   << "FLASER 3 1 1 1 9 9 9 9.0 9.0 0.9 0.5 host 0.5\n"
                   << "FLASER 3 1 1 1 9 9 9 9.0 9.0 0.9 2.0 host 2.0\n"
                   << "FLASER 3 1 1 1 9 9 9 9.0 9.0 0.9 3.0 host 3.0\n"
                   << "FLASER 3 1 1 1 9 9 9 9.0 9.0 0.9 4.0 host 4.0\n";
  LogReadOptions opt;
  opt.odometry = OdometrySource::OdomLines;
  ScanLogInfo info;
  const auto scans = readScanLog(p.string(), opt, info);
  ASSERT_EQ(scans.size(), 4u);
  EXPECT_EQ(info.odometry_fallbacks, 2u);
  EXPECT_EQ(scans[0].odometry.x, 9.0);
  EXPECT_DOUBLE_EQ(scans[1].odometry.x, 2.0);
  EXPECT_DOUBLE_EQ(scans[1].odometry.y, 1.0);
  EXPECT_DOUBLE_EQ(scans[1].odometry.phi, 0.3);
  EXPECT_EQ(scans[2].odometry.x, 3.0);
  EXPECT_EQ(scans[3].odometry.x, 9.0);
}

TEST(LogReader, ReadsAces) {
  const auto scans = readScanLog(kAces);
  ASSERT_EQ(scans.size(), 7374u);
  EXPECT_EQ(scans.front().scan.timestamp, 70.2899);  // relative timestamps
  EXPECT_EQ(scans.back().scan.timestamp, 1435.809999);
}

TEST(LogReader, IntelThroughBothRawlogLayoutsGivesTheSameStream) {
  const auto& in = intel();
  for (const auto layout : {RawlogLayout::ActionSensoryFrame, RawlogLayout::ObservationOnly}) {
    SCOPED_TRACE(rawlogLayoutName(layout));
    // Content decides the format: a gzip rawlog named like a CARMEN log is still read as a rawlog.
    const fs::path p = tmpDir() / (std::string("intel_") + rawlogLayoutName(layout) + ".clf.gz");
    RawlogWriteOptions opt;
    opt.layout = layout;
    writeRawlog(p.string(), in, opt);
    EXPECT_EQ(detectLogFormat(p.string()), LogFormat::Rawlog);
    ScanLogInfo info;
    const auto out = readScanLog(p.string(), {}, info);
    EXPECT_EQ(info.rawlog_has_actions, layout == RawlogLayout::ActionSensoryFrame);
    ASSERT_EQ(out.size(), in.size());
    double worst_beam = 0, worst_odo = 0;
    std::size_t ts_mismatch = 0, validity_mismatch = 0;
    const mrpt::poses::CPose2D p0(in[0].odometry.x, in[0].odometry.y, in[0].odometry.phi);
    for (std::size_t i = 0; i < in.size(); ++i) {
      ts_mismatch += out[i].scan.timestamp != in[i].scan.timestamp;
      validity_mismatch += out[i].scan.valid != in[i].scan.valid;
      worst_beam = std::max(worst_beam, maxEndpointError(in[i].scan, out[i].scan));
      mrpt::poses::CPose2D expected(in[i].odometry.x, in[i].odometry.y, in[i].odometry.phi);
      if (layout == RawlogLayout::ActionSensoryFrame) expected = expected - p0;
      worst_odo = std::max(worst_odo, std::hypot(out[i].odometry.x - expected.x(), out[i].odometry.y - expected.y()));
    }
    EXPECT_EQ(ts_mismatch, 0u);
    EXPECT_EQ(validity_mismatch, 0u);
    EXPECT_LT(worst_beam, 1e-9);
    EXPECT_LT(worst_odo, 1e-9);
  }
}

// A CARMEN log's scans come with the geometry that MRPT's observation holds exactly (useMrptScanGeometry): the
// MRPT map builder, fed the same log as CObservation2DRangeScans, sees the very same numbers.
TEST(LogReader, CarmenScansHoldTheGeometryOfTheirMrptObservationBitForBit) {
  std::size_t differ = 0;
  for (const auto& log : {kIntel, kAces}) {
    const auto scans = log == kIntel ? intel() : readScanLog(log);
    for (const ScanRecord& r : scans) {
      const LaserScan back = fromMrptScan(*toMrptScan(r.scan));
      differ += back.timestamp != r.scan.timestamp || back.start_angle != r.scan.start_angle ||
                back.angle_increment != r.scan.angle_increment || back.max_range != r.scan.max_range ||
                back.sensor_pose.x != r.scan.sensor_pose.x || back.sensor_pose.y != r.scan.sensor_pose.y ||
                back.sensor_pose.phi != r.scan.sensor_pose.phi || back.ranges != r.scan.ranges;
    }
  }
  EXPECT_EQ(differ, 0u);
  // The FLASER fan of 180 beams from -90 deg: its centre, -0.5 deg, is in the laser's yaw now, and the beams
  // are symmetric about it; every beam points where it did.
  const LaserScan& s = intel().front().scan;
  EXPECT_NEAR(s.sensor_pose.phi, -0.5 * M_PI / 180.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.start_angle, -89.5 * M_PI / 180.0);
  EXPECT_NEAR(s.sensor_pose.phi + s.beamAngle(0), -M_PI / 2, 1e-12);
}

TEST(LogReader, SniffsContentNotExtension) {
  // A CARMEN text log named .rawlog is still CARMEN.
  const fs::path p = tmpDir() / "text.rawlog";
  std::ofstream(p) << "# comment\nFLASER 3 1 2 3 0 0 0 0 0 0 5.5 host 5.5\n";
  EXPECT_EQ(detectLogFormat(p.string()), LogFormat::Carmen);
  const auto scans = readScanLog(p.string());
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_EQ(scans[0].scan.timestamp, 5.5);
  const fs::path e = tmpDir() / "empty.clf";
  std::ofstream(e).close();
  EXPECT_EQ(detectLogFormat(e.string()), LogFormat::Empty);
  EXPECT_TRUE(readScanLog(e.string()).empty());
  EXPECT_THROW(detectLogFormat((tmpDir() / "nope.clf").string()), gridtopo::InputError);
  // A folder given as the log says so.
  try {
    detectLogFormat(tmpDir().string());
    ADD_FAILURE() << "a folder was read as a log";
  } catch (const gridtopo::InputError& e) {
    EXPECT_EQ(e.file(), tmpDir().string());
    EXPECT_NE(std::string(e.what()).find("is a folder, not a log file"), std::string::npos) << e.what();
  }
}

TEST(LogReader, MalformedCarmenLineNamesFileLineAndField) {
  const fs::path p = tmpDir() / "bad.clf";
  std::ofstream(p) << "FLASER 3 1 2 3 0 0 0 0 0 0 5.5 host 5.5\nFLASER 3 1 x 3 0 0 0 0 0 0 5.6 host 5.6\n";
  try {
    readScanLog(p.string());
    FAIL();
  } catch (const gridtopo::InputError& e) {
    EXPECT_EQ(e.file(), p.string());
    EXPECT_EQ(e.line(), 2u);
  }
  LogReadOptions opt;
  opt.carmen.skip_bad_lines = true;
  ScanLogInfo info;
  EXPECT_EQ(readScanLog(p.string(), opt, info).size(), 1u);
  EXPECT_EQ(info.skipped_lines, 1u);
}

TEST(LogReader, CarmenWithNonAsciiCommentsIsStillCarmen) {
  const fs::path p = tmpDir() / "utf8.clf";
  std::ofstream(p) << "# recorded by Dirk H\xc3\xa4hnel, \xc2\xb0 and \xc3\xa9\n"
                   << "FLASER 3 1 2 3 0 0 0 0 0 0 5.5 host 5.5\n";
  EXPECT_EQ(detectLogFormat(p.string()), LogFormat::Carmen);
  EXPECT_EQ(readScanLog(p.string()).size(), 1u);
  // Binary junk that is no MRPT object is handed to the CARMEN parser, which names the line.
  const fs::path junk = tmpDir() / "junk.bin";
  std::ofstream(junk, std::ios::binary) << std::string("\x01\x02\x03\xff\xfe garbage\n", 14);
  EXPECT_EQ(detectLogFormat(junk.string()), LogFormat::Carmen);
  try {
    readScanLog(junk.string());
    FAIL() << "junk accepted";
  } catch (const gridtopo::InputError& e) {
    EXPECT_EQ(e.line(), 1u);
  }
}
