// CARMEN reader: the bundled Intel and ACES logs (exact counts and first/last values from datasets/README.md
// and the files themselves) and a synthetic log exercising every quirk the reader claims to handle.
#include <gtest/gtest.h>

#include "common/scratch.h"
#include <zlib.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/io/carmen_log.h"

namespace fs = std::filesystem;
using namespace gridtopo;
using namespace gridtopo::io;
using gridtopo::InputError;

namespace {
constexpr double kDeg = M_PI / 180.0;

std::string dataPath(const std::string& rel) { return std::string(GRIDTOPO_DATA_DIR) + "/" + rel; }

CarmenLog parse(const std::string& text, const CarmenReadOptions& o = {}) {
  std::istringstream in(text);
  return parseCarmenLog(in, "test.clf", o);
}

/// Expects parsing `text` to throw an InputError at `line` whose field is `field`.
void expectError(const std::string& text, std::size_t line, const std::string& field) {
  try {
    parse(text);
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "test.clf");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
  }
}

/// One gzip member holding `s`, compressed in memory.
std::string gzipString(const std::string& s) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);  // 15 + 16: gzip wrapper
  std::string out(deflateBound(&z, s.size()), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(s.data()));
  z.avail_in = static_cast<uInt>(s.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

std::string flaser(const std::vector<std::string>& ranges, const std::string& laser, const std::string& odom,
                   const std::string& ipc, const std::string& logger) {
  std::string s = "FLASER " + std::to_string(ranges.size());
  for (const auto& r : ranges) s += " " + r;
  return s + " " + laser + " " + odom + " " + ipc + " nohost " + logger + "\n";
}
std::vector<std::string> constantRanges(std::size_t n, const std::string& v) { return std::vector<std::string>(n, v); }
}  // namespace

TEST(CarmenLog, IntelCountsAndValues) {
  const auto t0 = std::chrono::steady_clock::now();
  const CarmenLog log = readCarmenLog(dataPath("slam/intel.clf.gz"));
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "Intel loaded in " << secs << " s\n";
  ASSERT_EQ(log.scans.size(), 13631u);
  ASSERT_EQ(log.odometry.size(), 26915u);
  EXPECT_EQ(log.lines, 40557u);
  EXPECT_EQ(log.skipped_lines, 0u);
  EXPECT_EQ(log.params.at("robot_frontlaser_offset"), "0.0");
  // A healthy log: nothing decided against its word (its backward timestamp steps are kept, see below).
  EXPECT_TRUE(log.warnings.empty());
  EXPECT_TRUE(log.skipped_messages.empty());

  const ScanRecord& first = log.scans.front();
  EXPECT_EQ(first.source_index, 13u);
  EXPECT_EQ(first.scan.timestamp, 976052857.337530);  // exactly the parsed double
  EXPECT_EQ(first.scan.logger_timestamp, 0.000246);
  ASSERT_EQ(first.scan.size(), 180u);
  EXPECT_FLOAT_EQ(first.scan.ranges[0], 1.07f);
  EXPECT_TRUE(first.has_odometry);
  EXPECT_DOUBLE_EQ(first.odometry.phi, -0.002458);
  EXPECT_NEAR(first.scan.start_angle, -M_PI / 2, 1e-12);
  EXPECT_NEAR(first.scan.angle_increment, kDeg, 1e-12);
  EXPECT_NEAR(first.scan.beamAngle(179), 89 * kDeg, 1e-12);
  EXPECT_EQ(first.scan.sensor_pose, mrpt::math::TPose2D(0, 0, 0));
  EXPECT_DOUBLE_EQ(first.scan.max_range, 50.0);

  const ScanRecord& last = log.scans.back();
  EXPECT_EQ(last.source_index, 40556u);
  EXPECT_EQ(last.scan.timestamp, 976055548.624744);
  EXPECT_EQ(last.scan.logger_timestamp, 2691.287460);
  EXPECT_FLOAT_EQ(last.scan.ranges[0], 1.00f);
  EXPECT_FLOAT_EQ(last.scan.ranges[179], 1.12f);
  EXPECT_DOUBLE_EQ(last.odometry.x, -50.883999);
  EXPECT_DOUBLE_EQ(last.odometry.y, -35.825001);
  EXPECT_DOUBLE_EQ(last.odometry.phi, 2.538102);

  EXPECT_EQ(log.odometry.front().timestamp, 976052857.337284);
  EXPECT_EQ(log.odometry.front().source_index, 12u);
  EXPECT_EQ(log.odometry.back().timestamp, 976055548.625127);
  EXPECT_EQ(log.odometry.back().logger_timestamp, 2691.287843);

  // Quirks of this log: 631 backward steps of the laser ipc timestamps, 68 313 "no return" readings (81.83 m).
  std::size_t backwards = 0, no_return = 0, invalid = 0;
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    if (i > 0 && log.scans[i].scan.timestamp < log.scans[i - 1].scan.timestamp) ++backwards;
    const auto& s = log.scans[i].scan;
    for (std::size_t k = 0; k < s.size(); ++k) {
      no_return += s.isNoReturn(k);
      invalid += !s.valid[k];
    }
  }
  EXPECT_EQ(backwards, 631u);
  EXPECT_EQ(no_return, 68313u);
  EXPECT_EQ(invalid, 68313u);
  EXPECT_NEAR(log.scans.back().scan.logger_timestamp - log.scans.front().scan.logger_timestamp, 2691.3, 0.05);
}

TEST(CarmenLog, AcesCountsAndValues) {
  const CarmenLog log = readCarmenLog(dataPath("slam/aces.clf.gz"));
  ASSERT_EQ(log.scans.size(), 7374u);
  ASSERT_EQ(log.odometry.size(), 7375u);
  EXPECT_EQ(log.params.size(), 4u);
  EXPECT_TRUE(log.warnings.empty());
  const auto& first = log.scans.front();
  EXPECT_EQ(first.source_index, 15u);
  EXPECT_EQ(first.scan.timestamp, 70.289900);  // relative timestamps
  EXPECT_FLOAT_EQ(first.scan.ranges[0], 46.56f);
  EXPECT_TRUE(first.scan.valid[0]);
  EXPECT_DOUBLE_EQ(first.odometry.phi, -1.570796);
  const auto& last = log.scans.back();
  EXPECT_EQ(last.scan.timestamp, 1435.809999);
  EXPECT_DOUBLE_EQ(last.odometry.x, -17.805700);
  EXPECT_EQ(log.odometry.back().timestamp, 1435.900000);
  std::size_t no_return = 0;
  for (const auto& r : log.scans)
    for (std::size_t k = 0; k < r.scan.size(); ++k) no_return += r.scan.isNoReturn(k);
  EXPECT_EQ(no_return, 11139u);  // the 50.00 m readings
}

TEST(CarmenLog, PlainAndGzipGiveTheSameResult) {
  const std::string text = "# comment\r\nPARAM robot_front_laser_max 20 nohost 0\r\n" +
                           flaser(constantRanges(180, "1.5"), "1 2 0.5", "1 2 0.5", "10.5", "0.5");
  const CarmenLog a = parse(text);
  const CarmenLog b = parse(gzipString(text));
  ASSERT_EQ(a.scans.size(), 1u);
  ASSERT_EQ(b.scans.size(), 1u);
  EXPECT_EQ(a.scans[0].scan.ranges, b.scans[0].scan.ranges);
  EXPECT_EQ(a.scans[0].scan.max_range, 20.0);
  EXPECT_EQ(b.scans[0].scan.max_range, 20.0);
  // Concatenated gzip members are one stream.
  const CarmenLog c = parse(gzipString(text) + gzipString(flaser(constantRanges(180, "2"), "0 0 0", "0 0 0", "11", "1")));
  EXPECT_EQ(c.scans.size(), 2u);
}

TEST(CarmenLog, TruncatedOrCorruptGzipIsAnInputError) {
  std::string text;
  for (int i = 0; i < 50; ++i)
    text += flaser(constantRanges(180, std::to_string(1 + i % 7) + ".25"), "0 0 0", "0 0 0", std::to_string(i), "0");
  const std::string gz = gzipString(text);
  for (std::size_t cut : {gz.size() - 1, gz.size() - 4, gz.size() - 8, gz.size() / 2, std::size_t(12), std::size_t(2)}) {
    try {
      parse(gz.substr(0, cut));
      ADD_FAILURE() << "truncated at " << cut << " parsed";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "gzip") << e.what();
    }
  }
  std::string corrupt = gz;
  corrupt[gz.size() / 2] = static_cast<char>(corrupt[gz.size() / 2] ^ 0x55);
  EXPECT_THROW(parse(corrupt), InputError);
  // Truncation is fatal even when the user asks to skip bad lines.
  CarmenReadOptions skip;
  skip.skip_bad_lines = true;
  EXPECT_THROW(parse(gz.substr(0, gz.size() / 2), skip), InputError);
  // A file on disk too.
  const fs::path p = gridtopo::test::scratch("truncated") / "log.clf.gz";
  std::ofstream(p, std::ios::binary) << gz.substr(0, gz.size() - 3);
  EXPECT_THROW(readCarmenLog(p.string()), InputError);
  EXPECT_THROW(readCarmenLog("/nonexistent/log.clf"), InputError);
}

TEST(CarmenLog, BeamCountsGiveTheApertureOfTheCarmenConvention) {
  struct Case {
    std::size_t n;
    double inc_deg, last_deg;
  };
  for (const Case c : {Case{180, 1.0, 89.0}, Case{181, 1.0, 90.0}, Case{360, 0.5, 89.5}, Case{361, 0.5, 90.0}}) {
    // Mixed 180/181-beam scans in one log are fine: each line is taken on its own.
    const CarmenLog log = parse(flaser(constantRanges(c.n, "3"), "0 0 0", "0 0 0", "1", "1") +
                                flaser(constantRanges(181, "3"), "0 0 0", "0 0 0", "2", "2"));
    ASSERT_EQ(log.scans.size(), 2u);
    const LaserScan& s = log.scans[0].scan;
    EXPECT_EQ(s.size(), c.n);
    EXPECT_NEAR(s.start_angle, -90 * kDeg, 1e-12) << c.n;
    EXPECT_NEAR(s.angle_increment, c.inc_deg * kDeg, 1e-12) << c.n;
    EXPECT_NEAR(s.beamAngle(c.n - 1), c.last_deg * kDeg, 1e-9) << c.n;
    EXPECT_NEAR(log.scans[1].scan.beamAngle(180), 90 * kDeg, 1e-9);
  }
  // PARAMs say otherwise: 0.5° resolution over a 100° field of view.
  const CarmenLog log = parse("PARAM laser_front_laser_resolution 0.5 nohost 0\nPARAM laser_front_laser_fov 100 h 0\n" +
                              flaser(constantRanges(201, "3"), "0 0 0", "0 0 0", "1", "1"));
  EXPECT_NEAR(log.scans[0].scan.start_angle, -50 * kDeg, 1e-12);
  EXPECT_NEAR(log.scans[0].scan.angle_increment, 0.5 * kDeg, 1e-12);
}

TEST(CarmenLog, SyntheticLogWithEveryQuirk) {
  std::ostringstream t;
  t << "# CARMEN log written by the test\n"
    << "\n"
    << "   # indented comment\n"
    << "PARAM robot_frontlaser_offset 0.25 nohost 0\n"
    << "PARAM robot_front_laser_max 30.0 nohost 0\n"
    << "PARAM robot_name my robot with spaces nohost 0\n"
    << "SYNC tag 1.0 nohost 0.1\n"
    << "TRUEPOS 1 2 3 4 5 6 1.0 nohost 0.1\n"
    << "NMEA-GGA 1 2 3 4 5 6 7 8 9 10 11 12 13 1.0 nohost 0.1\n";
  // Line 10: FLASER with the laser 0.25 m ahead of a robot at (1, 2, 90°): laser world pose (1, 2.25, 90°).
  // Ranges: 30 (= max: no return), 45.5 (beyond), inf, nan, -1, 0, 81.83, then real returns.
  std::vector<std::string> r = constantRanges(181, "2.5");
  r[0] = "30";
  r[1] = "45.5";
  r[2] = "inf";
  r[3] = "nan";
  r[4] = "-1";
  r[5] = "0";
  r[6] = "81.83";
  r[7] = "29.999";
  t << flaser(r, "1 2.25 1.5707963267948966", "1 2 1.5707963267948966", "1002560357.218569", "0.000001");
  // Line 11: timestamps step backwards; the laser pose equals the robot pose, so the PARAM offset applies.
  t << flaser(constantRanges(180, "1"), "4 5 0.1", "4 5 0.1", "1002560356.9", "0.1");
  // Line 12: ODOM.
  t << "ODOM 4.5 5.5 0.2 0.3 0.01 0 1002560357.5 nohost 0.2\n";
  // Lines 13-14: ROBOTLASER1 with alternating (interleaved) start angles, 361 beams at 0.5°, remissions.
  for (int i = 0; i < 2; ++i) {
    const double start = -M_PI / 2 + (i ? 0.25 * kDeg : 0.0);
    std::ostringstream l;
    l.precision(17);
    l << "ROBOTLASER1 0 " << start << " " << M_PI << " " << 0.5 * kDeg << " 8.0 0.01 0 361";
    for (int k = 0; k < 361; ++k) l << " " << (k == 10 ? "8.0" : "3.25");
    l << " 2 0.5 0.7";
    // laser at (0.1, -0.05, 0.2) in the robot frame; robot at (2, 3, 0).
    l << " 2.1 2.95 0.2 2 3 0 0.1 0.0 0.5 0.3 0 " << (1002560358.0 + i) << " host " << (1.0 + i) << "\n";
    t << l.str();
  }
  // Line 15: RLASER (rear laser) ignored unless asked; line 16: GMapping's NEFF line.
  t << "RLASER 180";
  for (int k = 0; k < 180; ++k) t << " 1.5";
  t << " 0 0 3.141592653589793 0 0 0 1002560359 nohost 3\n";
  t << "NEFF 15\n";
  const CarmenLog log = parse(t.str());
  ASSERT_EQ(log.scans.size(), 4u);
  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_EQ(log.params.at("robot_name"), "my robot with spaces");
  EXPECT_EQ(log.lines, 16u);
  const std::map<std::string, std::size_t> skipped = {
      {"NEFF", 1}, {"NMEA-GGA", 1}, {"RLASER", 1}, {"SYNC", 1}, {"TRUEPOS", 1}};
  EXPECT_EQ(log.skipped_messages, skipped);

  const ScanRecord& a = log.scans[0];
  EXPECT_EQ(a.source_index, 10u);
  EXPECT_EQ(a.scan.timestamp, 1002560357.218569);
  EXPECT_EQ(a.scan.logger_timestamp, 0.000001);
  EXPECT_EQ(a.scan.max_range, 30.0);
  EXPECT_NEAR(a.scan.sensor_pose.x, 0.25, 1e-12);
  EXPECT_NEAR(a.scan.sensor_pose.y, 0.0, 1e-12);
  EXPECT_NEAR(a.scan.sensor_pose.phi, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(a.odometry.x, 1.0);
  EXPECT_DOUBLE_EQ(a.odometry.y, 2.0);
  EXPECT_EQ(a.scan.size(), 181u);
  const std::vector<int> valid = {0, 0, 0, 0, 0, 0, 0, 1, 1};
  const std::vector<int> no_return = {1, 1, 1, 0, 0, 0, 1, 0, 0};
  for (std::size_t k = 0; k < valid.size(); ++k) {
    EXPECT_EQ(a.scan.valid[k], valid[k]) << k;
    EXPECT_EQ(a.scan.isNoReturn(k), no_return[k] == 1) << k;
  }
  EXPECT_FLOAT_EQ(a.scan.ranges[1], 45.5f);  // kept as logged
  EXPECT_FLOAT_EQ(a.scan.ranges[6], 81.83f);
  EXPECT_TRUE(std::isnan(a.scan.ranges[3]));

  const ScanRecord& b = log.scans[1];
  EXPECT_LT(b.scan.timestamp, a.scan.timestamp);
  EXPECT_EQ(b.scan.timestamp, 1002560356.9);
  EXPECT_NEAR(b.scan.sensor_pose.x, 0.25, 1e-12);  // PARAM fallback

  const ScanRecord& c = log.scans[2];
  const ScanRecord& d = log.scans[3];
  EXPECT_EQ(c.scan.size(), 361u);
  EXPECT_NEAR(c.scan.start_angle, -M_PI / 2, 1e-12);
  EXPECT_NEAR(d.scan.start_angle, -M_PI / 2 + 0.25 * kDeg, 1e-12);
  EXPECT_NEAR(c.scan.angle_increment, 0.5 * kDeg, 1e-12);
  EXPECT_EQ(c.scan.max_range, 8.0);
  EXPECT_FALSE(c.scan.valid[10]);
  EXPECT_TRUE(c.scan.valid[11]);
  EXPECT_NEAR(c.scan.sensor_pose.x, 0.1, 1e-9);
  EXPECT_NEAR(c.scan.sensor_pose.y, -0.05, 1e-9);
  EXPECT_NEAR(c.scan.sensor_pose.phi, 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(c.odometry.x, 2.0);
  EXPECT_EQ(c.scan.timestamp, 1002560358.0);

  const auto& o = log.odometry[0];
  EXPECT_EQ(o.source_index, 12u);
  EXPECT_DOUBLE_EQ(o.pose.x, 4.5);
  EXPECT_DOUBLE_EQ(o.tv, 0.3);
  EXPECT_DOUBLE_EQ(o.rv, 0.01);
  EXPECT_EQ(o.timestamp, 1002560357.5);

  CarmenReadOptions rear;
  rear.read_rear_laser = true;
  const CarmenLog with_rear = parse(t.str(), rear);
  ASSERT_EQ(with_rear.scans.size(), 5u);
  EXPECT_NEAR(std::abs(with_rear.scans[4].scan.sensor_pose.phi), M_PI, 1e-9);  // facing backwards
}

TEST(CarmenLog, LaserOnlyLogsAndRawLaserLogs) {
  // A log with odometry only inside the laser lines (no ODOM).
  const CarmenLog a = parse(flaser(constantRanges(180, "1"), "1 1 0", "1 1 0", "5", "0"));
  EXPECT_TRUE(a.odometry.empty());
  EXPECT_TRUE(a.scans[0].has_odometry);
  // A log with no odometry at all (RAWLASER1 only): scans without odometry.
  std::ostringstream l;
  l << "RAWLASER1 0 -1.5707963 3.1415926 0.0174533 81.9 0.01 0 180";
  for (int k = 0; k < 180; ++k) l << " 2.0";
  l << " 0 12.5 host 0.5\n";
  const CarmenLog b = parse(l.str());
  ASSERT_EQ(b.scans.size(), 1u);
  EXPECT_FALSE(b.scans[0].has_odometry);
  EXPECT_EQ(b.scans[0].scan.timestamp, 12.5);
  EXPECT_NEAR(b.scans[0].scan.max_range, 81.9, 1e-12);
  // RAWLASER1 beside posed scans is a duplicate of them and is dropped.
  const CarmenLog c = parse(l.str() + flaser(constantRanges(180, "1"), "1 1 0", "1 1 0", "12.5", "0.5"));
  EXPECT_EQ(c.scans.size(), 1u);
  EXPECT_TRUE(c.scans[0].has_odometry);
}

TEST(CarmenLog, ErrorsNameLineAndField) {
  const std::string ok = flaser(constantRanges(180, "1"), "0 0 0", "0 0 0", "1", "1");
  auto bad_range = constantRanges(180, "1");
  bad_range[16] = "1.0x";
  expectError(ok + flaser(bad_range, "0 0 0", "0 0 0", "2", "2"), 2, "FLASER range 17");
  expectError(ok + ok + flaser(constantRanges(180, "1"), "0 nan 0", "0 0 0", "2", "2"), 3, "FLASER y");
  expectError(flaser(constantRanges(180, "1"), "0 0 0", "0 0 inf", "2", "2"), 1, "FLASER odom_theta");
  expectError(flaser(constantRanges(180, "1"), "0 0 0", "0 0 0", "abc", "2"), 1, "FLASER ipc_timestamp");
  expectError(flaser(constantRanges(180, "1"), "0 0 0", "0 0 0", "1", "2x"), 1, "FLASER logger_timestamp");
  expectError(flaser(constantRanges(179, "1"), "0 0 0", "0 0 0", "1", "2").replace(7, 3, "180"), 1, "FLASER");
  expectError("FLASER 18o 1 2\n", 1, "FLASER num_readings");
  expectError("FLASER -3 1 2\n", 1, "FLASER num_readings");
  expectError("FLASER 0 0 0 0 0 0 0 1 h 1\n", 1, "FLASER num_readings");
  expectError("FLASER 99999999999 1 2\n", 1, "FLASER num_readings");
  expectError("ODOM 1 2 3 4 5 6 7 h\n", 1, "ODOM");
  expectError("ODOM 1 2 3 4 5 6 7 h 8 9\n", 1, "ODOM");
  expectError("ODOM 1 2 NaN 4 5 6 7 h 8\n", 1, "ODOM theta");
  expectError("ODOM 1 2 3 4 5 6 7 h 8\nthis is garbage\n", 2, "message");
  expectError("FOOBAR 1 2 3\n", 1, "message");
  expectError("PARAM robot_frontlaser_offset abc nohost 0\n", 1, "PARAM robot_frontlaser_offset");
  expectError("PARAM robot_front_laser_max -5 nohost 0\n", 1, "PARAM robot_front_laser_max");
  expectError("PARAM x 0\n", 1, "PARAM");
  expectError("PARAM x 1 nohost abc\n", 1, "PARAM logger_timestamp");
  expectError("ROBOTLASER1 0 -1.57 3.14 0.0174 81 0.01 0 3 1 2 3 0 0 0 0 0 0 0 0 0 0 0\n", 1, "ROBOTLASER1");
  expectError("ROBOTLASER1 0 -1.57 3.14 0.0174 81 0.01 0 3 1 2 3 1 0.5 0 0 0 x 0 0 0 0 0 0 0 1 h 1\n", 1,
              "ROBOTLASER1 robot_x");

  try {
    parse(ok + flaser(bad_range, "0 0 0", "0 0 0", "2", "2"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "test.clf:2: FLASER range 17: not a number ('1.0x')");
  }
}

TEST(CarmenLog, SkipBadLinesCountsAndReports) {
  const std::string ok = flaser(constantRanges(180, "1"), "0 0 0", "0 0 0", "1", "1");
  CarmenReadOptions o;
  o.skip_bad_lines = true;
  const CarmenLog log = parse(ok + "garbage line\n" + ok + "ODOM 1 2 nan 4 5 6 7 h 8\nFLASER 180 1 2\n" + ok, o);
  EXPECT_EQ(log.scans.size(), 3u);
  EXPECT_EQ(log.skipped_lines, 3u);
  ASSERT_EQ(log.skipped.size(), 3u);
  EXPECT_NE(log.skipped[0].find("test.clf:2:"), std::string::npos);
  EXPECT_NE(log.skipped[1].find("test.clf:4: ODOM theta"), std::string::npos);
  EXPECT_EQ(log.scans[2].source_index, 6u);
}

TEST(CarmenLog, EmptyLogIsEmpty) {
  const CarmenLog log = parse("# nothing\n");
  EXPECT_TRUE(log.scans.empty());
  EXPECT_TRUE(log.odometry.empty());
  EXPECT_EQ(log.lines, 1u);
}

TEST(CarmenLog, ExtremeRangeValues) {
  auto r = constantRanges(180, "1");
  r[0] = "1e300";    // finite double beyond float: +inf, no return
  r[1] = "-1e300";   // negative: no information
  r[2] = "1e-999";   // underflow: zero, no information
  r[3] = "+2.5";     // explicit sign
  r[4] = "Infinity";
  const CarmenLog log = parse(flaser(r, "0 0 0", "0 0 0", "1", "1"));
  const LaserScan& s = log.scans.at(0).scan;
  EXPECT_TRUE(std::isinf(s.ranges[0]) && s.ranges[0] > 0);
  EXPECT_TRUE(s.isNoReturn(0));
  EXPECT_FALSE(s.valid[1]);
  EXPECT_FALSE(s.isNoReturn(1));
  EXPECT_FALSE(s.valid[2]);
  EXPECT_FALSE(s.isNoReturn(2));
  EXPECT_TRUE(s.valid[3]);
  EXPECT_FLOAT_EQ(s.ranges[3], 2.5f);
  EXPECT_TRUE(s.isNoReturn(4));
}
