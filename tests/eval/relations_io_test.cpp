// Relations files and corrected CARMEN logs (timestamp matching) on synthetic data.
#include <gtest/gtest.h>

#include "common/scratch.h"
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/eval/corrected_log.h"
#include "gridtopo/eval/relations.h"
#include "gridtopo/io/carmen_log.h"

namespace fs = std::filesystem;
using namespace gridtopo;
using namespace gridtopo::eval;

namespace {
fs::path tmp(const std::string& name) { return gridtopo::test::scratchPath("eval_" + name); }

void writeGz(const fs::path& p, const std::string& s) {
  gzFile g = gzopen(p.c_str(), "wb9");
  gzwrite(g, s.data(), static_cast<unsigned>(s.size()));
  gzclose(g);
}

io::CarmenLog parseLog(const std::string& text, const std::string& name) {
  std::istringstream in(text);
  return io::parseCarmenLog(in, name);
}

std::string flaser(double r0, const std::string& pose, const std::string& ipc, const std::string& logger) {
  std::string s = "FLASER 3 " + std::to_string(r0) + " 2 3 " + pose + " " + pose + " " + ipc + " h " + logger + "\n";
  return s;
}
}  // namespace

TEST(Relations, ParsesPlainAndGzip) {
  const std::string text =
      "# comment\n\n976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000 0.000000 0.000000 -1.682210\r\n"
      "  2 1 1e-3 +2 0 0 0 3.0\n";
  const auto a = parseRelations(text, "rel.txt");
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].t1, 976052905.167303);
  EXPECT_EQ(a[0].line, 3u);
  EXPECT_EQ(a[1].t1, 2.0);
  EXPECT_EQ(a[1].t2, 1.0);
  EXPECT_EQ(a[1].delta.y, 2.0);
  EXPECT_EQ(a[1].delta.phi, 3.0);
  const auto p = tmp("rel.gz");
  writeGz(p, text);
  const auto b = readRelations(p.string());
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0].t2, a[0].t2);
  std::ofstream(tmp("rel.txt")) << text;
  EXPECT_EQ(readRelations(tmp("rel.txt").string()).size(), 2u);
}

TEST(Relations, ErrorsNameLineAndField) {
  auto expect = [](const std::string& text, std::size_t line, const std::string& field) {
    try {
      parseRelations(text, "rel.txt");
      ADD_FAILURE() << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_EQ(e.field(), field) << e.what();
    }
  };
  expect("1 2 3 4 5 6 7 8\n1 2 3 nan 5 6 7 8\n", 2, "y");
  expect("1 2 3 4 5 6 7\n", 1, "yaw");
  expect("1 2 3 4 5 6 7 8 9\n", 1, "line");
  expect("1 2x 3 4 5 6 7 8\n", 1, "t2");
  expect("1 2 3 4 5 6 7 inf\n", 1, "yaw");
  EXPECT_THROW(readRelations("/nonexistent/rel"), InputError);
}

TEST(Relations, TruncatedGzipIsAnError) {
  std::string text;
  for (int i = 0; i < 2000; ++i) text += std::to_string(i) + " " + std::to_string(i + 1) + " 0.1 0.2 0 0 0 0.3\n";
  const auto p = tmp("rel_full.gz");
  writeGz(p, text);
  std::ifstream f(p, std::ios::binary);
  const std::string gz((std::istreambuf_iterator<char>(f)), {});
  for (std::size_t cut : {gz.size() - 2, gz.size() / 2, std::size_t(20)}) {
    const auto q = tmp("rel_cut.gz");
    std::ofstream(q, std::ios::binary) << gz.substr(0, cut);
    try {
      readRelations(q.string());
      ADD_FAILURE() << "truncated at " << cut;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "gzip") << e.what();
    }
  }
}

TEST(CorrectedLog, MatchesSixDigitLoggerTimestamps) {
  // Raw log: ipc = 5000 + logger. Two scans 1 ms apart around logger 1234.56 (a burst like Intel's).
  const std::string raw_text = flaser(1.0, "0 0 0", "5010.000001", "10.000001") +
                               flaser(1.5, "1 0 0", "6234.559", "1234.559") +
                               flaser(2.0, "2 0 0", "6234.5612", "1234.5612") +
                               flaser(2.5, "3 0 0", "6300.25", "1300.25");
  const auto raw = parseLog(raw_text, "raw.clf");
  // Corrected log (GMapping style): 6 significant digits, ipc = logger; the second line's ranges are those
  // of the raw scan at 1234.5612 but its printed time 1234.56 is nearer to 1234.559.
  const std::string gfs_text = flaser(1.0, "0.5 0.5 0.1", "10", "10") + "NEFF 15\n" +
                               flaser(2.0, "2.5 0.5 0.2", "1234.56", "1234.56") +
                               flaser(2.5, "3.5 0.5 0.3", "1300.25", "1300.25");
  const auto gfs = parseLog(gfs_text, "gfs.log");
  CorrectedTimeMatch used;
  const auto est = correctedTrajectory(gfs.scans, gfs.path, raw.scans, raw.path, {}, &used);
  EXPECT_EQ(used, CorrectedTimeMatch::Logger);
  ASSERT_EQ(est.size(), 3u);
  EXPECT_EQ(est[0].timestamp, 5010.000001);
  EXPECT_EQ(est[1].timestamp, 6234.559);  // nearest logger timestamp (the reference convention)
  EXPECT_EQ(est[2].timestamp, 6300.25);
  EXPECT_DOUBLE_EQ(est[1].pose.x, 2.5);
  EXPECT_DOUBLE_EQ(est[1].pose.phi, 0.2);

  CorrectedLogOptions by_ranges;
  by_ranges.match = CorrectedTimeMatch::LoggerAndRanges;
  const auto exact = correctedTrajectory(gfs.scans, gfs.path, raw.scans, raw.path, by_ranges);
  EXPECT_EQ(exact[1].timestamp, 6234.5612);  // the scan with the same ranges

  // A corrected log stamped with the raw ipc timestamps is used as is (auto -> ipc).
  const auto ipc_log = parseLog(flaser(2.0, "7 7 0", "6234.5612", "0"), "ipc.log");
  const auto e2 = correctedTrajectory(ipc_log.scans, ipc_log.path, raw.scans, raw.path, {}, &used);
  EXPECT_EQ(used, CorrectedTimeMatch::Ipc);
  EXPECT_EQ(e2[0].timestamp, 6234.5612);

  // No raw scan within the printed precision: an error naming the corrected log's line and field.
  const auto bad = parseLog(flaser(1.0, "0 0 0", "10", "10") + flaser(1.0, "0 0 0", "1250.5", "1250.5"), "bad.log");
  try {
    correctedTrajectory(bad.scans, bad.path, raw.scans, raw.path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.log");
    EXPECT_EQ(e.line(), 2u);
    EXPECT_EQ(e.field(), "logger_timestamp");
  }
  CorrectedLogOptions ipc_only;
  ipc_only.match = CorrectedTimeMatch::Ipc;
  EXPECT_THROW(correctedTrajectory(gfs.scans, gfs.path, raw.scans, raw.path, ipc_only), InputError);
  EXPECT_THROW(correctedTrajectory({}, "empty.log", raw.scans, raw.path), InputError);
}

TEST(CorrectedLog, RobotOrLaserPose) {
  const auto raw = parseLog(flaser(1.0, "0 0 0", "100", "1"), "raw.clf");
  // Laser 0.2 m ahead of the robot at (1, 1, 90°): laser world pose (1, 1.2, 90°).
  const auto gfs = parseLog("FLASER 3 1 2 3 1 1.2 1.5707963267948966 1 1 1.5707963267948966 100 h 1\n", "gfs");
  const auto robot = correctedTrajectory(gfs.scans, gfs.path, raw.scans, raw.path);
  EXPECT_NEAR(robot[0].pose.y, 1.0, 1e-12);
  CorrectedLogOptions o;
  o.pose = CorrectedPose::Laser;
  const auto laser = correctedTrajectory(gfs.scans, gfs.path, raw.scans, raw.path, o);
  EXPECT_NEAR(laser[0].pose.x, 1.0, 1e-12);
  EXPECT_NEAR(laser[0].pose.y, 1.2, 1e-12);
}
