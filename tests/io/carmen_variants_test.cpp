// CARMEN reader on the variants real logs come in: both PARAM layouts, fov / resolution PARAMs in radians, a
// declared max range the readings contradict, a no-return code below the declared max, degenerate timestamps
// (too few digits, all zero, wrapping), the CARMEN message table (used, skipped and counted, unknown),
// ROBOTLASER-only and 361-beam FLASER logs, and the bundled MIT CSAIL (both layouts), Freiburg hospital,
// Intel, ACES and FR079 logs when they are present.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <utility>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/io/carmen_log.h"
#include "gridtopo/io/scan_conversion.h"

using namespace gridtopo;
using namespace gridtopo::io;
using gridtopo::InputError;

namespace {
constexpr double kDeg = M_PI / 180.0;

CarmenLog parse(const std::string& text, const CarmenReadOptions& o = {}) {
  std::istringstream in(text);
  return parseCarmenLog(in, "test.clf", o);
}

std::string fixed(double v, int decimals = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

/// FLASER line with `n` ranges given by `range(k)`; laser and odometry poses as text.
template <class RangeFn>
std::string flaser(std::size_t n, RangeFn range, const std::string& laser, const std::string& odom,
                   const std::string& ipc, const std::string& logger) {
  std::string s = "FLASER " + std::to_string(n);
  for (std::size_t k = 0; k < n; ++k) s += " " + range(k);
  return s + " " + laser + " " + odom + " " + ipc + " nohost " + logger + "\n";
}
std::string flaser(std::size_t n, const std::string& r, const std::string& ipc = "1", const std::string& logger = "1") {
  return flaser(n, [&](std::size_t) { return r; }, "0 0 0", "0 0 0", ipc, logger);
}

/// ROBOTLASER1 line, CARMEN writer's layout (angles in radians, no remissions).
template <class RangeFn>
std::string robotlaser(double start, std::size_t n, RangeFn range, double max_range, const std::string& laser,
                       const std::string& robot, const std::string& ipc, const std::string& logger) {
  std::ostringstream l;
  l.precision(17);
  l << "ROBOTLASER1 0 " << start << " " << M_PI << " " << kDeg << " " << max_range << " 0.01 0 " << n;
  for (std::size_t k = 0; k < n; ++k) l << " " << range(k);
  l << " 0 " << laser << " " << robot << " 0 0 0.5 0.3 0 " << ipc << " zoidberg2 " << logger << "\n";
  return l.str();
}

bool contains(const std::vector<std::string>& v, const std::string& part) {
  for (const auto& s : v)
    if (s.find(part) != std::string::npos) return true;
  return false;
}
std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += "  " + x + "\n";
  return s;
}
}  // namespace

// ---------------------------------------------------------------------------------------------------------
// 1. PARAM layouts

TEST(CarmenParam, CarmenLoggerLayoutWithIpcTimestamp) {
  // The standard CARMEN logger writes `PARAM name value ipc_timestamp host logger_timestamp`; the old reader
  // stopped at the first line with "expected one numeric value".
  const std::string text = "PARAM robot_frontlaser_offset -0.04 1071078718.462495 merci 1071078718.462494\n"
                           "PARAM robot_name my robot 1071078718.462500 merci 1071078718.462501\n"
                           "PARAM robot_front_laser_max 30 1071078718.500000 merci 1071078718.500000\n" +
                           flaser(180, "2", "1071078719.000000", "0.1");
  const CarmenLog log = parse(text);
  EXPECT_EQ(log.params.at("robot_frontlaser_offset"), "-0.04");
  EXPECT_EQ(log.params.at("robot_name"), "my robot");
  ASSERT_EQ(log.scans.size(), 1u);
  EXPECT_NEAR(log.scans[0].scan.sensor_pose.x, -0.04, 1e-12);
  EXPECT_EQ(log.scans[0].scan.max_range, 30.0);
  EXPECT_TRUE(contains(log.notes, "3 PARAM lines read as `PARAM name value ipc_timestamp host logger_timestamp`"))
      << joined(log.notes);
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
  // A parameter change logged later carries the logger's relative time: it follows the file's layout.
  const CarmenLog later = parse(text + "PARAM robot_front_laser_max 20 1071078800.000000 merci 81.500000\n");
  EXPECT_EQ(later.params.at("robot_front_laser_max"), "20");
  EXPECT_EQ(later.scans[0].scan.max_range, 20.0);
}

TEST(CarmenParam, OldLayoutAndAmbiguousLinesFollowTheFile) {
  // Five tokens: only `name value host logger` leaves a value, even if the value is a number.
  CarmenLog log = parse("PARAM x 0.0 host 12.5\n");
  EXPECT_EQ(log.params.at("x"), "0.0");
  EXPECT_TRUE(log.warnings.empty());

  // An old file (5-token lines) with a multi-number value whose last number equals the logger time: the
  // file's layout wins, the line is reported.
  log = parse("PARAM robot_frontlaser_offset 0.1 nohost 0\nPARAM robot_use_laser on nohost 0\n"
              "PARAM robot_laser_pose 0.1 0.0 0.0 nohost 0\n");
  EXPECT_EQ(log.params.at("robot_laser_pose"), "0.1 0.0 0.0");
  EXPECT_EQ(log.params.at("robot_frontlaser_offset"), "0.1");
  EXPECT_TRUE(contains(log.warnings, "(line 3) also fit")) << joined(log.warnings);

  // A non-numeric token before the host can only be the old layout: the whole file is read that way.
  log = parse("PARAM robot_name my robot nohost 0\nPARAM a 1 2 h 2\n");
  EXPECT_EQ(log.params.at("robot_name"), "my robot");
  EXPECT_EQ(log.params.at("a"), "1 2");
  EXPECT_TRUE(contains(log.warnings, "(line 2) also fit")) << joined(log.warnings);

  // Only undecided lines (number before the host, far from the logger time): the data lines' ipc timestamps
  // decide. Within a day of them: the ipc layout.
  const std::string param = "PARAM robot_front_laser_max 20 1071078700.000000 merci 81.500000\n";
  log = parse(param + flaser(180, "2", "1071078719.000000", "82.0"));
  EXPECT_EQ(log.scans.at(0).scan.max_range, 20.0);
  EXPECT_TRUE(contains(log.warnings, "PARAM layout undecided")) << joined(log.warnings);
  // Far from them (relative data timestamps): the old layout, and a numeric PARAM with two numbers is a clear
  // error rather than a silent misread.
  try {
    parse(param + flaser(180, "2", "5.0", "5.0"));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 1u);
    EXPECT_EQ(e.field(), "PARAM robot_front_laser_max");
    EXPECT_NE(std::string(e.what()).find("expected one numeric value"), std::string::npos) << e.what();
  }
  // A new-layout file with a 5-token line reads that line the only way it has a value.
  log = parse("PARAM a 1 1071078718.462495 merci 1071078718.462494\nPARAM b 2 1071078718.5 m 1071078718.5\n"
              "PARAM c 3 m 1071078718.5\n");
  EXPECT_EQ(log.params.at("a"), "1");
  EXPECT_EQ(log.params.at("c"), "3");
  EXPECT_TRUE(contains(log.warnings, "have 5 tokens")) << joined(log.warnings);
}

// ---------------------------------------------------------------------------------------------------------
// 2. Units of the fov / resolution PARAMs

TEST(CarmenGeometry, FieldOfViewInRadians) {
  // Read as degrees, 3.14159 would make the 181 beams span -1.6° .. +1.6° in 0.017° steps.
  CarmenLog log = parse("PARAM laser_front_laser_fov 3.14159 nohost 0\n" + flaser(181, "3"));
  const LaserScan& s = log.scans.at(0).scan;
  EXPECT_NEAR(s.start_angle, -M_PI / 2, 1e-5);
  EXPECT_NEAR(s.angle_increment, kDeg, 1e-7);
  EXPECT_NEAR(s.beamAngle(180), M_PI / 2, 1e-5);
  EXPECT_TRUE(contains(log.warnings, "PARAM laser_front_laser_fov 3.14159 read as radians (180 deg)"))
      << joined(log.warnings);
  // 180 beams: the CARMEN convention, -90° .. +89°.
  log = parse("PARAM laser_front_laser_fov 3.14159 nohost 0\n" + flaser(180, "3"));
  EXPECT_NEAR(log.scans[0].scan.beamAngle(179), 89 * kDeg, 1e-5);
  // Degrees as documented: no warning.
  log = parse("PARAM laser_front_laser_fov 180 nohost 0\nPARAM laser_front_laser_resolution 1 nohost 0\n" +
              flaser(181, "3"));
  EXPECT_NEAR(log.scans[0].scan.start_angle, -M_PI / 2, 1e-12);
  EXPECT_NEAR(log.scans[0].scan.angle_increment, kDeg, 1e-12);
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
  // More than 360 (degrees or radians) is an error.
  EXPECT_THROW(parse("PARAM laser_front_laser_fov 400 nohost 0\n"), InputError);
}

TEST(CarmenGeometry, ResolutionInRadiansDecidedByTheBeamCount) {
  // fov in degrees, resolution in radians: 361 × 0.5° = 180°.
  CarmenLog log = parse("PARAM laser_front_laser_fov 180 nohost 0\n"
                        "PARAM laser_front_laser_resolution 0.00872665 nohost 0\n" + flaser(361, "3"));
  EXPECT_NEAR(log.scans.at(0).scan.angle_increment, 0.5 * kDeg, 1e-8);
  EXPECT_NEAR(log.scans[0].scan.start_angle, -M_PI / 2, 1e-12);
  EXPECT_NEAR(log.scans[0].scan.beamAngle(360), M_PI / 2, 1e-5);
  EXPECT_TRUE(contains(log.warnings, "laser_front_laser_resolution 0.00872665 read as radians (0.5 deg)"))
      << joined(log.warnings);
  // Both in radians.
  log = parse("PARAM laser_front_laser_fov 3.141593 nohost 0\nPARAM laser_front_laser_resolution 0.017453 nohost 0\n" +
              flaser(181, "3"));
  EXPECT_NEAR(log.scans[0].scan.start_angle, -M_PI / 2, 1e-6);
  EXPECT_NEAR(log.scans[0].scan.angle_increment, kDeg, 1e-6);
  EXPECT_EQ(log.warnings.size(), 2u) << joined(log.warnings);
  // Resolution alone, in radians: 180 beams over the default 180°, -90° .. +89°.
  log = parse("PARAM laser_front_laser_resolution 0.0174533 nohost 0\n" + flaser(180, "3"));
  EXPECT_NEAR(log.scans[0].scan.start_angle, -M_PI / 2, 1e-6);
  EXPECT_NEAR(log.scans[0].scan.beamAngle(179), 89 * kDeg, 1e-5);
  // Resolution alone, in degrees, not matching 180°: the scan is centred on the beams it has (181 × 0.5° =
  // 90°, -45° .. +45°) rather than starting at -90°.
  log = parse("PARAM laser_front_laser_resolution 0.5 nohost 0\n" + flaser(181, "3"));
  EXPECT_NEAR(log.scans[0].scan.start_angle, -45 * kDeg, 1e-12);
  EXPECT_NEAR(log.scans[0].scan.beamAngle(180), 45 * kDeg, 1e-12);
  // fov and resolution that disagree with the beam count in every unit: kept, with a warning.
  log = parse("PARAM laser_front_laser_fov 180 nohost 0\nPARAM laser_front_laser_resolution 0.5 nohost 0\n" +
              flaser(181, "3"));
  EXPECT_NEAR(log.scans[0].scan.angle_increment, 0.5 * kDeg, 1e-12);
  EXPECT_NEAR(log.scans[0].scan.start_angle, -M_PI / 2, 1e-12);
  EXPECT_TRUE(contains(log.warnings, "disagree with the 181-beam scans")) << joined(log.warnings);
}

// ---------------------------------------------------------------------------------------------------------
// 3. Max range

namespace {
/// 20 scans of 181 beams: beams 0..169 from 0.5 m to 51 m (varying a little per scan), beams 170..180 the
/// no-return code 81.91 if `code`.
std::string farReadingScans(bool code) {
  std::string t;
  for (int i = 0; i < 20; ++i)
    t += flaser(
        181,
        [&](std::size_t k) { return k >= 170 ? (code ? std::string("81.91") : fixed(3.0, 2)) : fixed(0.5 + 0.297 * k + 0.01 * i, 2); },
        "0 0 0", "0 0 0", std::to_string(10 + i), std::to_string(i));
  return t;
}
}  // namespace

TEST(CarmenMaxRange, DeclaredMaxContradictedByTheReadings) {
  // Declared 10 m, readings up to 51 m: the old reader made every reading beyond 10 m a no-return.
  CarmenLog log = parse("PARAM robot_front_laser_max 10 nohost 0\n" + farReadingScans(true));
  ASSERT_EQ(log.scans.size(), 20u);
  const LaserScan& s = log.scans[0].scan;
  EXPECT_FLOAT_EQ(static_cast<float>(s.max_range), 81.91f);
  EXPECT_TRUE(s.valid[100]);  // 30.2 m
  EXPECT_TRUE(s.valid[169]);  // 50.7 m
  EXPECT_FALSE(s.valid[175]);
  EXPECT_TRUE(s.isNoReturn(175));
  EXPECT_TRUE(contains(log.warnings, "PARAM robot_front_laser_max = 10 m is contradicted by the readings"))
      << joined(log.warnings);
  EXPECT_TRUE(contains(log.warnings, "max range set to 81.91 m, the no-return code (220 readings)"))
      << joined(log.warnings);

  // Without a no-return code: just above the largest reading, which stays a real return.
  log = parse("PARAM robot_front_laser_max 10 nohost 0\n" + farReadingScans(false));
  EXPECT_GT(log.scans[19].scan.max_range, 50.88);
  EXPECT_LT(log.scans[19].scan.max_range, 50.8801);
  EXPECT_TRUE(log.scans[19].scan.valid[169]);
  EXPECT_TRUE(contains(log.warnings, "no no-return code found")) << joined(log.warnings);

  // No PARAM: CARMEN's default of 50 m is overruled the same way.
  log = parse(farReadingScans(true));
  EXPECT_FLOAT_EQ(static_cast<float>(log.scans[0].scan.max_range), 81.91f);
  EXPECT_TRUE(contains(log.warnings, "the default max range (no PARAM robot_front_laser_max) = 50 m"))
      << joined(log.warnings);

  // A few stray readings beyond the declared max (35.5, 36.5, 37.5 m) do not overrule it: they stay
  // no-returns, noted.
  std::string stray = "PARAM robot_front_laser_max 30 nohost 0\n";
  for (int i = 0; i < 20; ++i)
    stray += flaser(181, [&](std::size_t k) { return k == 0 && i < 3 ? fixed(35.5 + i, 1) : std::string("2.5"); },
                    "0 0 0", "0 0 0", std::to_string(i), std::to_string(i));
  log = parse(stray);
  EXPECT_EQ(log.scans[0].scan.max_range, 30.0);
  EXPECT_TRUE(log.scans[0].scan.isNoReturn(0));
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
  EXPECT_TRUE(contains(log.notes, "3 readings lie beyond PARAM robot_front_laser_max = 30 m")) << joined(log.notes);
}

TEST(CarmenMaxRange, ReadingsAtMaxRangeAreNoReturns) {
  // ROBOTLASER1 max 81.9 (Freiburg): 81.91 and 81.9 are no-returns, a lone 81.83 (no spike of them: see
  // NoReturnCodeBelowTheDeclaredMax) a real return; FLASER with the default 50 m: 50.00 (ACES's no-return) is
  // a no-return, a lone 49.99 a real return.
  const std::vector<std::string> r = {"81.91", "81.9", "81.83", "5.0"};
  const CarmenLog log = parse(
      robotlaser(-M_PI / 2, 181, [&](std::size_t k) { return r[std::min<std::size_t>(k, 3)]; }, 81.9, "0 0 0",
                 "0 0 0", "1", "1") +
      flaser(180, [](std::size_t k) { return k == 0 ? std::string("50.00") : std::string(k == 1 ? "49.99" : "5.0"); },
             "0 0 0", "0 0 0", "2", "2"));
  const LaserScan& a = log.scans.at(0).scan;
  EXPECT_TRUE(a.isNoReturn(0));
  EXPECT_TRUE(a.isNoReturn(1));
  EXPECT_TRUE(a.valid[2]);
  EXPECT_TRUE(a.valid[3]);
  const LaserScan& b = log.scans.at(1).scan;
  EXPECT_EQ(b.max_range, 50.0);
  EXPECT_TRUE(b.isNoReturn(0));
  EXPECT_FALSE(b.valid[0]);
  EXPECT_TRUE(b.valid[1]);
}

namespace {
/// 20 ROBOTLASER1 scans of 181 beams declaring `declared`: beams 0..149 real hits from 0.5 m to 45 m, beams
/// 150..159 real hits near the top, spread over values (73.2 m to 81.2 m, a different one per beam and scan),
/// beams 160..171 the no-return code `code`, beams 172..180 `above` (another code beyond the declaration, as
/// the hospital's 81.91) unless empty.
std::string codeBelowMaxScans(double declared, const std::string& code, const std::string& above = "") {
  std::string t;
  for (int i = 0; i < 20; ++i)
    t += robotlaser(
        -M_PI / 2, 181,
        [&](std::size_t k) {
          if (k >= 172 && !above.empty()) return above;
          if (k >= 160) return code;
          if (k >= 150) return fixed(73.2 + 0.85 * static_cast<double>(k - 150) + 0.019 * i, 2);
          return fixed(0.5 + 0.3 * static_cast<double>(k) + 0.01 * i, 2);
        },
        declared, "0 0 0", "0 0 0", std::to_string(10 + i), std::to_string(i));
  return t;
}
}  // namespace

TEST(CarmenMaxRange, NoReturnCodeBelowTheDeclaredMax) {
  // MIT CSAIL's ROBOTLASER1 layout: the lines declare 81.92 m and write 81.91 for no return. The old reader
  // read those as hits (free space out to 81.9 m and an obstacle there).
  CarmenLog log = parse(codeBelowMaxScans(81.92, "81.91", "81.91"));
  ASSERT_EQ(log.scans.size(), 20u);
  for (const ScanRecord& r : log.scans) {
    const LaserScan& s = r.scan;
    EXPECT_EQ(s.max_range, static_cast<double>(81.91f));
    for (std::size_t k = 0; k < 160; ++k) EXPECT_TRUE(s.valid[k]) << k << " " << s.ranges[k];
    for (std::size_t k = 160; k < 181; ++k) EXPECT_TRUE(s.isNoReturn(k)) << k;
  }
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
  EXPECT_TRUE(contains(log.notes, "420 readings of 81.91 m (11.6 %) lie below the max_range field of the "
                                  "ROBOTLASER1 lines = 81.92 m: the no-return code"))
      << joined(log.notes);

  // The Freiburg hospital: declared 81.9 m, 81.91 beyond it (a no-return already) and a second code, 81.83,
  // below it: both are no-returns, the spread readings below them stay hits.
  log = parse(codeBelowMaxScans(81.9, "81.83", "81.91"));
  for (const ScanRecord& r : log.scans) {
    const LaserScan& s = r.scan;
    EXPECT_EQ(s.max_range, static_cast<double>(81.83f));
    EXPECT_TRUE(s.valid[159]);  // up to 81.2 m
    for (std::size_t k = 160; k < 181; ++k) EXPECT_TRUE(s.isNoReturn(k)) << k;
  }
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
  EXPECT_TRUE(contains(log.notes, "240 readings of 81.83 m (6.6 %) lie below the max_range field of the "
                                  "ROBOTLASER1 lines = 81.9 m: the no-return code"))
      << joined(log.notes);

  // The max range is the float the readings hold: it survives the float round trip the log reader applies
  // (useMrptScanGeometry, MRPT's observation stores a float max range), and every code reading, stored as a
  // float, still compares >= it as prepareScan compares it (in double) and as MRPT does (in float).
  for (ScanRecord& r : log.scans) {
    LaserScan& s = r.scan;
    useMrptScanGeometry(s);
    EXPECT_EQ(s.max_range, static_cast<double>(81.83f));
    for (std::size_t k = 160; k < 172; ++k) {
      EXPECT_GE(static_cast<double>(s.ranges[k]), s.max_range);
      EXPECT_GE(s.ranges[k], static_cast<float>(s.max_range));
    }
    EXPECT_LT(static_cast<double>(s.ranges[159]), s.max_range);
    const auto obs = toMrptScan(s);
    EXPECT_EQ(obs->maxRange, 81.83f);
    EXPECT_FALSE(obs->getScanRangeValidity(165));
    EXPECT_TRUE(obs->getScanRangeValidity(159));
  }
  // A declared 81.83 (the double) sits a hair below the float 81.83 the readings hold: the readings are at or
  // above it either way, and the code search leaves such a max range alone (nothing lies below it).
  EXPECT_LT(81.83, static_cast<double>(81.83f));
}

TEST(CarmenMaxRange, TopReadingsSpreadOverValuesAreHits) {
  // Real hits near the declared max, spread over neighbouring values as surfaces are (no spike), and a
  // repeated value among them only a few times as frequent as its neighbours: the declaration stands and
  // every one of them is a hit.
  std::string t;
  for (int i = 0; i < 20; ++i)
    t += robotlaser(
        -M_PI / 2, 181,
        [&](std::size_t k) {
          if (k >= 170) return std::string("78.40");  // 220 readings of one value...
          if (k >= 120) return fixed(77.9 + 0.02 * static_cast<double>(k - 120) + 0.001 * i, 3);  // ...1000 around it
          return fixed(0.5 + 0.3 * static_cast<double>(k) + 0.01 * i, 2);
        },
        81.92, "0 0 0", "0 0 0", std::to_string(10 + i), std::to_string(i));
  const CarmenLog log = parse(t);
  for (const ScanRecord& r : log.scans) {
    EXPECT_EQ(r.scan.max_range, 81.92);
    for (std::size_t k = 0; k < 181; ++k) EXPECT_TRUE(r.scan.valid[k]) << k;
  }
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
  EXPECT_FALSE(contains(log.notes, "no-return code")) << joined(log.notes);
  // Fewer than 20 readings of a value are no code either, however lonely.
  std::string few;
  for (int i = 0; i < 3; ++i)
    few += robotlaser(-M_PI / 2, 181, [&](std::size_t k) { return k < 5 ? std::string("81.5") : std::string("3.0"); },
                      81.92, "0 0 0", "0 0 0", std::to_string(10 + i), std::to_string(i));
  const CarmenLog lonely = parse(few);
  EXPECT_TRUE(lonely.scans[0].scan.valid[0]);
  EXPECT_EQ(lonely.scans[0].scan.max_range, 81.92);
}

// ---------------------------------------------------------------------------------------------------------
// 4. Timestamps

namespace {
/// 30 FLASER lines (5 Hz) with an ODOM line after every second one; ipc and logger texts per index.
template <class Ipc, class Logger>
std::string timedLog(Ipc ipc, Logger logger) {
  std::string t;
  for (int i = 0; i < 30; ++i) {
    t += flaser(180, [](std::size_t) { return std::string("2"); }, "0 0 0", "0 0 0", ipc(i, false), logger(i, false));
    if (i % 2 == 1)
      t += "ODOM 0 0 0 0 0 0 " + ipc(i, true) + " nohost " + logger(i, true) + "\n";
  }
  return t;
}
std::string healthyLogger(int i, bool odom) { return fixed(0.2 * i + (odom ? 0.05 : 0.0)); }
}  // namespace

TEST(CarmenTimestamps, DegenerateIpcTimestampsFallBackToTheLoggerTimestamps) {
  // Unix time printed with 6 significant digits: every line says 1.07108e+09.
  CarmenLog log = parse(timedLog([](int, bool) { return std::string("1.07108e+09"); }, healthyLogger));
  ASSERT_EQ(log.scans.size(), 30u);
  ASSERT_EQ(log.odometry.size(), 15u);
  for (int i = 0; i < 30; ++i) EXPECT_NEAR(log.scans[i].scan.timestamp, 0.2 * i, 1e-9) << i;
  for (int j = 0; j < 15; ++j) EXPECT_NEAR(log.odometry[j].timestamp, 0.2 * (2 * j + 1) + 0.05, 1e-9) << j;
  EXPECT_TRUE(contains(log.warnings, "laser ipc timestamps are unusable (all 30 equal to 1071080000)"))
      << joined(log.warnings);
  EXPECT_TRUE(contains(log.warnings, "is its logger timestamp instead")) << joined(log.warnings);

  // All zero.
  log = parse(timedLog([](int, bool) { return std::string("0.000000"); }, healthyLogger));
  EXPECT_NEAR(log.scans[29].scan.timestamp, 5.8, 1e-9);
  EXPECT_TRUE(contains(log.warnings, "all 30 equal to 0")) << joined(log.warnings);

  // Wrapping (a 32-bit microsecond counter, -2147.48 s after +2147.48 s), with a healthy logger.
  auto wrapped = [](int i, bool odom) {
    double t = 2147.0 + 0.2 * i + (odom ? 0.05 : 0.0);
    if (t > 2147.483648) t -= 4294.967296;
    return fixed(t);
  };
  log = parse(timedLog(wrapped, healthyLogger));
  EXPECT_NEAR(log.scans[29].scan.timestamp, 5.8, 1e-9);
  EXPECT_TRUE(contains(log.warnings, "1 jump(s) back by up to 4294.77 s")) << joined(log.warnings);
}

TEST(CarmenTimestamps, RepairedInPlaceWhenTheLoggerTimestampsAreDegenerateToo) {
  auto zero = [](int, bool) { return std::string("0"); };
  // Whole seconds at 5 Hz: runs of five equal values spread by line order (the last run at the mean rate).
  CarmenLog log = parse(timedLog([](int i, bool odom) { return fixed(std::floor(1000.0 + 0.2 * i + (odom ? 0.05 : 0)), 0); }, zero));
  for (int i = 0; i < 30; ++i) EXPECT_NEAR(log.scans[i].scan.timestamp, 1000.0 + 0.2 * i, 1e-9) << i;
  EXPECT_TRUE(contains(log.warnings, "24 of 29 consecutive lines share their value")) << joined(log.warnings);
  EXPECT_TRUE(contains(log.warnings, "repaired in place")) << joined(log.warnings);
  for (std::size_t j = 1; j < log.odometry.size(); ++j)
    EXPECT_GT(log.odometry[j].timestamp, log.odometry[j - 1].timestamp) << j;

  // Wrapping: undone by adding the jump plus the typical step.
  log = parse(timedLog(
      [](int i, bool odom) {
        double t = 2147.0 + 0.2 * i + (odom ? 0.05 : 0.0);
        if (t > 2147.483648) t -= 4294.967296;
        return fixed(t);
      },
      zero));
  for (int i = 0; i < 30; ++i) EXPECT_NEAR(log.scans[i].scan.timestamp, 2147.0 + 0.2 * i, 1e-6) << i;
  for (int j = 0; j < 15; ++j) EXPECT_NEAR(log.odometry[j].timestamp, 2147.05 + 0.2 * (2 * j + 1), 1e-6) << j;

  // Nothing to go by: left as read, and said so.
  log = parse(timedLog(zero, zero));
  EXPECT_EQ(log.scans[29].scan.timestamp, 0.0);
  EXPECT_TRUE(contains(log.warnings, "the log holds no usable time")) << joined(log.warnings);
  // Absurd values whose repair would overflow: left as read (finite), and said so.
  log = parse(timedLog([](int i, bool) { return std::string(i < 15 ? "1e308" : "-1e308"); }, zero));
  EXPECT_EQ(log.scans[29].scan.timestamp, -1e308);
  EXPECT_TRUE(contains(log.warnings, "the log holds no usable time")) << joined(log.warnings);
}

TEST(CarmenTimestamps, HealthyTimestampsAreNeverChanged) {
  // Intel-like: laser ipc timestamps step back by up to 0.9 s now and then (two processes): kept exactly.
  auto jitter = [](int i, bool odom) { return fixed(976052857.0 + 0.2 * i + (i % 7 == 3 ? -0.9 : 0.0) + (odom ? 0.05 : 0)); };
  CarmenLog log = parse(timedLog(jitter, healthyLogger));
  for (int i = 0; i < 30; ++i) EXPECT_EQ(log.scans[i].scan.timestamp, std::stod(jitter(i, false))) << i;
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
  // Degenerate logger timestamps beside healthy ipc ones: reported, nothing changed.
  log = parse(timedLog(jitter, [](int, bool) { return std::string("0"); }));
  for (int i = 0; i < 30; ++i) EXPECT_EQ(log.scans[i].scan.timestamp, std::stod(jitter(i, false))) << i;
  EXPECT_EQ(log.scans[5].scan.logger_timestamp, 0.0);
  EXPECT_TRUE(contains(log.warnings, "laser logger timestamps look degenerate")) << joined(log.warnings);
  // Too few lines to judge: nothing is decided.
  log = parse(flaser(180, "2", "0", "0") + flaser(180, "2", "0", "0"));
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
}

// ---------------------------------------------------------------------------------------------------------
// 5. The CARMEN message table

TEST(CarmenMessages, UnusedMessagesAreSkippedAndCounted) {
  std::ostringstream t;
  t << "# CARMEN Logfile\n# message formats defined: PARAM SYNC ODOM RAWLASER1 RAWLASER2 RAWLASER3 RAWLASER4 "
       "ROBOTLASER0 ROBOTLASER1 FLASER RLASER LASER3 LASER4\n"
    << "PARAM robot_use_laser on nohost 0\n"
    << "SYNC tag 1.0 nohost 0.1\n"
    << "TRUEPOS 1 2 3 4 5 6 1.0 nohost 0.1\nTRUEPOS 1 2 3 4 5 6 1.2 nohost 0.3\n"
    << "NMEAGGA 1 2 3 N 4 E 1 5 1.0 0 0 0 0 0 1.0 nohost 0.1\n"
    << "RAWLASER2 0 -1.57 3.14 0.0175 81.9 0.01 0 3 1 1 1 0 1.0 nohost 0.1\n"
    << "RAWLASER1 0 -1.57 3.14 0.0175 81.9 0.01 0 3 1 1 1 0 1.0 nohost 0.1\n"  // beside FLASER: a duplicate
    << "LASER3 3 1 1 1 1.0 nohost 0.1\nREMISSIONFLASER 2 1 0.5 1 0.5 1.0 nohost 0.1\n"
    << "POSITIONLASER 1 0 0 0 0 0 0 1.0 nohost 0.1\nIMU 0 0 0 1 0 0 0 0 0 0 0 0 0 1.0 nohost 0.1\n"
    << "RLASER 3 1 1 1 0 0 0 0 0 0 1.0 nohost 0.1\n"  // rear laser, not asked for
    << "ROBOTLASER2 0 -1.57 3.14 0.0175 81.9 0.01 0 3 1 1 1 0 0 0 0 0 0 0 0 0 0 0 0 1.0 h 0.1\n"
    << "GPSPOSITION 48.0 7.8 1.0 nohost 0.1\nGPSPOSITION 48.1 7.8 1.2 nohost 0.3\n"  // a module we do not know
    << flaser(180, "2", "1.0", "0.1") << "ODOM 0 0 0 0 0 0 1.0 nohost 0.1\n";
  const CarmenLog log = parse(t.str());
  EXPECT_EQ(log.scans.size(), 1u);
  EXPECT_EQ(log.odometry.size(), 1u);
  const std::map<std::string, std::size_t> expected = {
      {"SYNC", 1},   {"TRUEPOS", 2},         {"NMEAGGA", 1},       {"RAWLASER2", 1}, {"RAWLASER1", 1},
      {"LASER3", 1}, {"REMISSIONFLASER", 1}, {"POSITIONLASER", 1}, {"IMU", 1},       {"RLASER", 1},
      {"ROBOTLASER2", 1}, {"GPSPOSITION", 2}};
  EXPECT_EQ(log.skipped_messages, expected);
  EXPECT_TRUE(contains(log.warnings, "unknown message type 'GPSPOSITION' (2 lines from line 16) skipped"))
      << joined(log.warnings);
  // Garbage stays an error: not a CARMEN line (lower case, or no `ipc host logger` ending).
  EXPECT_THROW(parse("this is garbage 1.0 host 2.0\n"), InputError);
  EXPECT_THROW(parse("FOOBAR 1 2 3\n"), InputError);
  EXPECT_THROW(parse("GPSPOSITION 48.0 7.8\n"), InputError);
  // With read_rear_laser the rear lines are read, not counted.
  CarmenReadOptions rear;
  rear.read_rear_laser = true;
  const CarmenLog with_rear = parse(t.str(), rear);
  EXPECT_EQ(with_rear.scans.size(), 3u);
  EXPECT_EQ(with_rear.skipped_messages.count("RLASER"), 0u);
}

TEST(CarmenMessages, FallbackLasersAndFlaserWithoutPoses) {
  auto robot0 = [](const std::string& ipc) {
    return "ROBOTLASER0 0 -1.5707963267948966 3.1415926535897931 0.017453292519943295 81.9 0.01 0 3 1 2 3 0 "
           "0.22 0 0 0 0 0 0 0 0 0 0 " + ipc + " h " + ipc + "\n";
  };
  // ROBOTLASER0 (named in some CARMEN headers) is the front laser of a log without any other.
  CarmenLog log = parse(robot0("1") + robot0("2"));
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_NEAR(log.scans[0].scan.sensor_pose.x, 0.22, 1e-12);
  EXPECT_TRUE(contains(log.notes, "ROBOTLASER0 lines read as the front laser")) << joined(log.notes);
  // Beside ROBOTLASER1 it is skipped and counted.
  log = parse(robot0("1") + robotlaser(-M_PI / 2, 3, [](std::size_t) { return 2; }, 81.9, "0 0 0", "0 0 0", "1", "1"));
  EXPECT_EQ(log.scans.size(), 1u);
  EXPECT_EQ(log.skipped_messages.at("ROBOTLASER0"), 1u);
  // FLASER lines without poses (n ranges, then the timestamps): scans without odometry.
  log = parse("PARAM robot_frontlaser_offset 0.1 nohost 0\nFLASER 3 1 2 3 5.5 host 0.5\nODOM 1 2 3 0 0 0 5.6 host 0.6\n");
  ASSERT_EQ(log.scans.size(), 1u);
  EXPECT_FALSE(log.scans[0].has_odometry);
  EXPECT_EQ(log.scans[0].scan.timestamp, 5.5);
  EXPECT_NEAR(log.scans[0].scan.sensor_pose.x, 0.1, 1e-12);
  EXPECT_NEAR(log.scans[0].scan.start_angle, -M_PI / 2, 1e-12);
  EXPECT_TRUE(contains(log.notes, "1 FLASER/RLASER lines without poses")) << joined(log.notes);
  // Token counts that fit neither form name both.
  try {
    parse("FLASER 3 1 2 3 0 0 5.5 host 0.5\n");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected 14 tokens for 3 readings (8 without poses), found 10"),
              std::string::npos)
        << e.what();
  }
}

// ---------------------------------------------------------------------------------------------------------
// 6. ROBOTLASER-only logs, interlaced start angles, 361-beam FLASER

TEST(CarmenRobotLaser, InterlacedStartAnglesAndOdometryFromTheLaserLines) {
  // Freiburg hospital style: no ODOM, no PARAM; the start angle steps 0.25° per scan and the scans alternate
  // 181 / 180 beams; the laser is 0.22 m ahead of the robot.
  std::string t;
  for (int i = 0; i < 8; ++i) {
    const double start = -M_PI / 2 + 0.25 * kDeg * (i % 4);
    const std::size_t n = i % 4 == 0 ? 181 : 180;
    const double x = 0.1 * i;
    t += robotlaser(start, n, [](std::size_t k) { return k == 5 ? 81.91 : 4.0; }, 81.9,
                    fixed(x + 0.22) + " 0 0", fixed(x) + " 0 0", fixed(1232658478.161285 + 0.6 * i), fixed(0.6 * i));
  }
  const CarmenLog log = parse(t);
  ASSERT_EQ(log.scans.size(), 8u);
  EXPECT_TRUE(log.odometry.empty());
  EXPECT_TRUE(contains(log.notes, "no ODOM lines: odometry is the robot pose inside the laser lines"))
      << joined(log.notes);
  for (int i = 0; i < 8; ++i) {
    const ScanRecord& r = log.scans[i];
    EXPECT_NEAR(r.scan.start_angle, -M_PI / 2 + 0.25 * kDeg * (i % 4), 1e-12) << i;
    EXPECT_EQ(r.scan.size(), i % 4 == 0 ? 181u : 180u);
    EXPECT_NEAR(r.scan.angle_increment, kDeg, 1e-12);
    EXPECT_TRUE(r.has_odometry);
    EXPECT_NEAR(r.odometry.x, 0.1 * i, 1e-9);
    EXPECT_NEAR(r.scan.sensor_pose.x, 0.22, 1e-6);
    EXPECT_EQ(r.scan.max_range, 81.9);
    EXPECT_TRUE(r.scan.isNoReturn(5));
    EXPECT_TRUE(r.scan.valid[4]);
  }
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
}

TEST(CarmenFlaser, Flaser361BeamsSpanMinus90ToPlus90Inclusive) {
  // MIT CSAIL style: 361 beams 0.5° apart, no PARAM, no ODOM, no-returns written as 81.91.
  const CarmenLog log = parse(flaser(361, [](std::size_t k) { return k == 7 ? std::string("81.91") : std::string("1.40"); },
                                     "576.536523 0.106594 -2.255213", "576.536523 0.106594 -2.255213",
                                     "1134864629.895182", "0.086295"));
  const LaserScan& s = log.scans.at(0).scan;
  EXPECT_EQ(s.size(), 361u);
  EXPECT_NEAR(s.angle_increment, 0.5 * kDeg, 1e-12);
  EXPECT_NEAR(s.beamAngle(0), -M_PI / 2, 1e-12);
  EXPECT_NEAR(s.beamAngle(180), 0.0, 1e-12);
  EXPECT_NEAR(s.beamAngle(360), M_PI / 2, 1e-12);
  EXPECT_TRUE(s.isNoReturn(7));
  EXPECT_TRUE(s.valid[8]);
  EXPECT_TRUE(log.scans[0].has_odometry);
  EXPECT_DOUBLE_EQ(log.scans[0].odometry.x, 576.536523);
}

// ---------------------------------------------------------------------------------------------------------
// The bundled logs that exercise these variants (datasets/slam; skipped when a checkout lacks them)

namespace {
/// The repository's datasets folder, else the shared datasets beside the checkout (../shared/datasets, where
/// the logs too large for the repository live, e.g. slam/mit-csail-robotlaser.clf.gz); "" when neither has it.
std::string dataPath(const std::string& rel) {
  const std::string dirs[] = {GRIDTOPO_DATA_DIR, std::string(GRIDTOPO_SOURCE_DIR) + "/../shared/datasets"};
  for (const std::string& dir : dirs)
    if (std::filesystem::exists(dir + "/" + rel)) return dir + "/" + rel;
  return "";
}
}  // namespace

TEST(CarmenBundledLogs, MitCsailFlaser361WithoutOdometry) {
  const std::string path = dataPath("slam/mit-csail.clf.gz");
  if (path.empty()) GTEST_SKIP() << "slam/mit-csail.clf.gz not present";
  const CarmenLog log = readCarmenLog(path);
  ASSERT_EQ(log.scans.size(), 1988u);
  EXPECT_TRUE(log.odometry.empty());
  EXPECT_TRUE(log.params.empty());
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
  EXPECT_TRUE(log.skipped_messages.empty());
  const ScanRecord& first = log.scans.front();
  EXPECT_EQ(first.source_index, 4u);
  EXPECT_EQ(first.scan.timestamp, 1134864629.895182);
  EXPECT_FLOAT_EQ(first.scan.ranges[0], 1.40f);
  EXPECT_NEAR(first.scan.beamAngle(360), M_PI / 2, 1e-12);
  EXPECT_DOUBLE_EQ(first.odometry.x, 576.536523);
  EXPECT_EQ(log.scans.back().scan.timestamp, 1134865053.892206);
  std::size_t no_return = 0;
  for (const auto& r : log.scans) {
    EXPECT_EQ(r.scan.size(), 361u);
    for (std::size_t k = 0; k < r.scan.size(); ++k) no_return += r.scan.isNoReturn(k);
  }
  EXPECT_EQ(no_return, 23711u);  // the 81.91 readings
}

TEST(CarmenBundledLogs, FreiburgClinicRobotLaserOnlyInterlaced) {
  const std::string path = dataPath("slam/fr-clinic.clf.gz");
  if (path.empty()) GTEST_SKIP() << "slam/fr-clinic.clf.gz not present";
  const CarmenLog log = readCarmenLog(path);
  ASSERT_EQ(log.scans.size(), 6917u);
  EXPECT_TRUE(log.odometry.empty());
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
  const ScanRecord& first = log.scans.front();
  EXPECT_EQ(first.scan.timestamp, 1232658478.161285);
  EXPECT_EQ(first.scan.logger_timestamp, -0.055208);
  EXPECT_EQ(first.scan.size(), 181u);
  EXPECT_NEAR(first.scan.start_angle, -1.570796, 1e-12);
  EXPECT_NEAR(first.scan.sensor_pose.x, 0.22, 1e-9);
  EXPECT_EQ(first.scan.max_range, static_cast<double>(81.83f));  // the no-return code below the declared 81.9
  EXPECT_NEAR(log.scans[1].scan.start_angle, -1.566433, 1e-12);
  std::map<double, std::size_t> starts;
  std::size_t beams181 = 0, no_return = 0;
  for (const auto& r : log.scans) {
    ++starts[r.scan.start_angle];
    beams181 += r.scan.size() == 181;
    EXPECT_TRUE(r.has_odometry);
    for (std::size_t k = 0; k < r.scan.size(); ++k) no_return += r.scan.isNoReturn(k);
  }
  EXPECT_EQ(starts.size(), 4u);
  EXPECT_EQ(beams181, 1748u);
  // The 150 066 readings of 81.91 (beyond the declared 81.9) and the 5 849 of 81.83, the second no-return code,
  // just below it.
  EXPECT_EQ(no_return, 155915u);
  EXPECT_TRUE(contains(log.notes, "5849 readings of 81.83 m (0.5 %) lie below the max_range field of the "
                                  "ROBOTLASER1 lines = 81.9 m: the no-return code"))
      << joined(log.notes);
}

TEST(CarmenBundledLogs, LogsWhoseTopReadingsAreHitsKeepTheirMaxRange) {
  // Intel and FR079 (codes 81.83 and 81.91 above their max of 50 and 80.99 m, real readings ending far below
  // it) and ACES (1 169 real readings in [45, 50) m spread over 112 values, its code 50.00 at the max): no code
  // is found below the max range, every scan keeps it.
  const std::vector<std::pair<std::string, double>> logs = {
      {"slam/intel.clf.gz", 50.0}, {"slam/aces.clf.gz", 50.0}, {"slam/fr079.clf.gz", 80.99}};
  std::size_t read = 0;
  for (const auto& [rel, max_range] : logs) {
    const std::string path = dataPath(rel);
    if (path.empty()) continue;
    ++read;
    const CarmenLog log = readCarmenLog(path);
    EXPECT_FALSE(contains(log.notes, "no-return code")) << rel << "\n" << joined(log.notes);
    std::size_t other = 0;
    for (const auto& r : log.scans) other += r.scan.max_range != max_range;
    EXPECT_EQ(other, 0u) << rel;
  }
  if (read == 0) GTEST_SKIP() << "none of the logs is present";
}

TEST(CarmenBundledLogs, MitCsailBothLayoutsGiveTheSameNoReturns) {
  // The same run in its original ROBOTLASER1 layout (declared max 81.92 m, no-return code 81.91 below it) and
  // converted to FLASER (no declaration: the default 50 m, the code above it): the same readings are
  // no-returns, beam for beam.
  const std::string flaser_path = dataPath("slam/mit-csail.clf.gz");
  const std::string robot_path = dataPath("slam/mit-csail-robotlaser.clf.gz");
  if (flaser_path.empty() || robot_path.empty()) GTEST_SKIP() << "a CSAIL layout is not present";
  const CarmenLog flaser_log = readCarmenLog(flaser_path);
  const CarmenLog robot_log = readCarmenLog(robot_path);
  ASSERT_EQ(flaser_log.scans.size(), 1988u);
  ASSERT_EQ(robot_log.scans.size(), flaser_log.scans.size());
  EXPECT_TRUE(robot_log.warnings.empty()) << joined(robot_log.warnings);
  EXPECT_TRUE(contains(robot_log.notes, "23711 readings of 81.91 m (3.3 %) lie below the max_range field of the "
                                        "ROBOTLASER1 lines = 81.92 m: the no-return code"))
      << joined(robot_log.notes);
  std::size_t flaser_no_return = 0, robot_no_return = 0, robot_hits = 0, differ = 0;
  for (std::size_t i = 0; i < flaser_log.scans.size(); ++i) {
    const LaserScan& a = flaser_log.scans[i].scan;
    const LaserScan& b = robot_log.scans[i].scan;
    ASSERT_EQ(a.size(), b.size()) << i;
    EXPECT_EQ(b.max_range, static_cast<double>(81.91f)) << i;
    for (std::size_t k = 0; k < a.size(); ++k) {
      flaser_no_return += a.isNoReturn(k);
      robot_no_return += b.isNoReturn(k);
      robot_hits += b.valid[k];
      differ += a.isNoReturn(k) != b.isNoReturn(k) || a.valid[k] != b.valid[k];
    }
  }
  EXPECT_EQ(flaser_no_return, 23711u);
  EXPECT_EQ(robot_no_return, 23711u);
  EXPECT_EQ(robot_hits, 1988u * 361u - 23711u);
  EXPECT_EQ(differ, 0u);
}
