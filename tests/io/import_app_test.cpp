// End-to-end tests of the gridtopo-import app; the rawlogs it writes are checked with MRPT's own loader.
#include <gtest/gtest.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include "test_tmp_dir.h"

namespace fs = std::filesystem;

using gridtopo::test::tmpDir;
using gridtopo::test::readText;

namespace {
const std::string kApp = std::string(GRIDTOPO_BIN_DIR) + "/gridtopo-import";
const std::string kIntel = std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.clf.gz";

struct Run {
  int status;
  std::string out, err;
};

Run run(const std::string& args) {
  const fs::path out = tmpDir() / "stdout.txt", err = tmpDir() / "stderr.txt";
  const std::string cmd = kApp + " " + args + " > " + out.string() + " 2> " + err.string();
  const int raw = std::system(cmd.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, readText(out), readText(err)};
}

// 180 ranges: 2.00 m everywhere except beam 10 (81.91 = no return) and beam 11 (0.00 = no information).
std::string flaser(double t, double x, int beams = 180) {
  std::ostringstream s;
  s << "FLASER " << beams;
  for (int k = 0; k < beams; ++k) s << (k == 10 ? " 81.91" : (k == 11 ? " 0.00" : " 2.00"));
  s.setf(std::ios::fixed);
  s.precision(6);
  s << ' ' << x << " 0 0 " << x << " 0 0 " << t << " host " << t << "\n";
  return s.str();
}
}  // namespace

TEST(ImportApp, HelpAndBadArguments) {
  auto r = run("--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("--layout"), std::string::npos);
  EXPECT_NE(r.out.find("--skip-bad-lines"), std::string::npos);
  r = run("-i " + kIntel + " --layout bogus");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("unknown rawlog layout"), std::string::npos);
  r = run("-i " + (tmpDir() / "missing.clf").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("missing.clf"), std::string::npos);
  r = run("");  // --input or --simulate is required
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--input or --simulate"), std::string::npos);
  // A failed run leaves no output behind: a bad input line with an output path given.
  const fs::path bad = tmpDir() / "bad.clf", out = tmpDir() / "never.rawlog";
  std::ofstream(bad) << "FLASER 3 1 2 x 0 0 0 0 0 0 1.0 host 1.0\n";
  r = run("-i " + bad.string() + " -o " + out.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(bad.string() + ":1:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(ImportApp, SimulatedLogWithGroundTruth) {
  const fs::path out = tmpDir() / "sim.rawlog", gt = tmpDir() / "sim_gt.txt";
  auto r = run("--simulate 50 --seed 3 -o " + out.string() + " --ground-truth " + gt.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("scans:              50\n"), std::string::npos) << r.out;
  mrpt::obs::CRawlog raw;
  ASSERT_TRUE(raw.loadFromRawLogFile(out.string()));
  EXPECT_EQ(raw.size(), 100u);
  std::ifstream f(gt);
  std::string line;
  std::size_t poses = 0;
  while (std::getline(f, line)) poses += !line.empty() && line[0] != '#';
  EXPECT_EQ(poses, 50u);
  r = run("--ground-truth " + gt.string() + " -i " + kIntel);
  EXPECT_EQ(r.status, 1);
}

TEST(ImportApp, QuirkyCarmenLogSummaryAndBadLines) {
  const fs::path log = tmpDir() / "quirks.clf";
  {
    std::ofstream f(log);
    f << "# a comment\nPARAM robot_front_laser_max 50.0 host 0\n"
      << "ODOM 0 0 0 0 0 0 100.0 host 100.0\n"
      << flaser(100.1, 0.0) << flaser(100.3, 0.1) << flaser(100.2, 0.2)  // timestamp steps back 0.1 s
      << "FLASER 180 1 2 oops\n"                                         // malformed: line 7
      << flaser(100.5, 0.3, 181) << "ODOM 1 0 0 0 0 0 101.0 host 101.0\n";
  }
  auto r = run("-i " + log.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(log.string() + ":7:"), std::string::npos) << r.err;

  const fs::path out = tmpDir() / "quirks.rawlog";
  r = run("-i " + log.string() + " --skip-bad-lines -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("scans:              4\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("beams per scan:     180 x 3 181 x 1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("backward steps:     1 (largest 0.1 s)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no-return readings: 4 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no-info readings:   4 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("skipped bad lines:  1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("odometry messages:  2 (ODOM lines)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("time span:          100.1 .. 100.5 (min 100.1, max 100.5, 0.4 s)"), std::string::npos) << r.out;

  mrpt::obs::CRawlog raw;
  ASSERT_TRUE(raw.loadFromRawLogFile(out.string()));
  ASSERT_EQ(raw.size(), 8u);
  const auto sf = raw.getAsObservations(7);
  const auto scan = sf->getObservationByClass<mrpt::obs::CObservation2DRangeScan>();
  ASSERT_TRUE(scan);
  EXPECT_EQ(scan->getScanSize(), 181u);  // 181 beams over 180 deg: symmetric, no yaw
  EXPECT_FLOAT_EQ(scan->aperture, static_cast<float>(M_PI));
  EXPECT_NEAR(scan->sensorPose.yaw(), 0.0, 1e-12);
  EXPECT_FLOAT_EQ(scan->maxRange, 50.0f);
  EXPECT_FALSE(scan->getScanRangeValidity(10));
  EXPECT_EQ(scan->getScanRange(10), 81.91f);  // the no-return reading is kept
  EXPECT_FALSE(scan->getScanRangeValidity(11));
  EXPECT_TRUE(scan->getScanRangeValidity(12));
  EXPECT_EQ(mrpt::Clock::toDouble(scan->timestamp), 100.5);

  // The same with ODOM-line odometry: the last scan (t = 100.5) sits halfway between ODOM x = 0 and x = 1.
  r = run("-i " + log.string() + " --skip-bad-lines --odometry odom --layout obs -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  mrpt::obs::CRawlog obs;
  ASSERT_TRUE(obs.loadFromRawLogFile(out.string()));
  ASSERT_EQ(obs.size(), 8u);
  const auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs.getAsObservation(6));
  ASSERT_TRUE(odo);
  EXPECT_NEAR(odo->odometry.x(), 0.5, 1e-12);
}

TEST(ImportApp, IntelToBothLayoutsIsAcceptedByMrpt) {
  const fs::path sf = tmpDir() / "intel_sf.rawlog", obs = tmpDir() / "intel_obs.rawlog";
  auto r = run("-i " + kIntel + " -o " + sf.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("scans:              13631\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("odometry messages:  26915 (ODOM lines)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("beams per scan:     180 x 13631\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("backward steps:     631 (largest 0.897325 s)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no-return readings: 68313 (2.78 % of 2453580 beams)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("sf layout, 27262 entries"), std::string::npos) << r.out;

  mrpt::obs::CRawlog raw;
  ASSERT_TRUE(raw.loadFromRawLogFile(sf.string()));
  ASSERT_EQ(raw.size(), 27262u);
  std::size_t scans = 0, actions = 0;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw.getType(i) == mrpt::obs::CRawlog::etActionCollection)
      ++actions;
    else if (raw.getType(i) == mrpt::obs::CRawlog::etSensoryFrame)
      scans += raw.getAsObservations(i)->getObservationByClass<mrpt::obs::CObservation2DRangeScan>() != nullptr;
  }
  EXPECT_EQ(actions, 13631u);
  EXPECT_EQ(scans, 13631u);
  const auto first = raw.getAsObservations(1)->getObservationByClass<mrpt::obs::CObservation2DRangeScan>();
  EXPECT_EQ(mrpt::Clock::toDouble(first->timestamp), 976052857.337530);
  EXPECT_EQ(first->getScanSize(), 180u);
  EXPECT_FLOAT_EQ(first->aperture, static_cast<float>(179.0 * M_PI / 180.0));
  EXPECT_NEAR(first->sensorPose.yaw(), -0.5 * M_PI / 180.0, 1e-15);
  EXPECT_TRUE(first->rightToLeft);
  EXPECT_FLOAT_EQ(first->getScanRange(0), 1.07f);

  r = run("-q -i " + kIntel + " --layout obs --gz -o " + obs.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  std::ifstream f(obs, std::ios::binary);
  EXPECT_EQ(f.get(), 0x1f);  // gzip
  mrpt::obs::CRawlog raw2;
  ASSERT_TRUE(raw2.loadFromRawLogFile(obs.string()));
  ASSERT_EQ(raw2.size(), 27262u);
  EXPECT_EQ(raw2.getType(0), mrpt::obs::CRawlog::etObservation);

  // Reading our rawlog back through the app gives the same summary numbers.
  r = run("-i " + obs.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("(MRPT rawlog, observation-only layout)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("backward steps:     631 (largest 0.897325 s)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no-return readings: 68313"), std::string::npos) << r.out;
}

TEST(ImportApp, AcesWithRelativeTimestamps) {
  const fs::path sf = tmpDir() / "aces_sf.rawlog.gz";
  const auto r = run("-i " + std::string(GRIDTOPO_DATA_DIR) + "/slam/aces.clf.gz -o " + sf.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("scans:              7374\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("odometry messages:  7375 (ODOM lines)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("time span:          70.2899 .. 1435.809999"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("backward steps:     0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no-return readings: 11139 "), std::string::npos) << r.out;
  mrpt::obs::CRawlog raw;
  ASSERT_TRUE(raw.loadFromRawLogFile(sf.string()));
  ASSERT_EQ(raw.size(), 14748u);
  const auto first = raw.getAsObservations(1)->getObservationByClass<mrpt::obs::CObservation2DRangeScan>();
  ASSERT_TRUE(first);
  EXPECT_EQ(mrpt::Clock::toDouble(first->timestamp), 70.2899);
  EXPECT_FLOAT_EQ(first->maxRange, 50.0f);
  const auto last = raw.getAsObservations(14747)->getObservationByClass<mrpt::obs::CObservation2DRangeScan>();
  EXPECT_EQ(mrpt::Clock::toDouble(last->timestamp), 1435.809999);
}

TEST(ImportApp, SummaryListsSkippedMessagesNotesAndWarnings) {
  // CARMEN-logger PARAM layout with the field of view in radians, and a message gridtopo does not use.
  const fs::path log = tmpDir() / "variants.clf";
  std::ofstream(log) << "PARAM laser_front_laser_fov 3.14159 1071078718.462495 merci 1071078718.462494\n"
                     << "TRUEPOS 1 2 3 4 5 6 100.0 nohost 0.1\n"
                     << flaser(100.1, 0.0, 181) << flaser(100.3, 0.1, 181);
  const auto r = run("-i " + log.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("first scan:         181 beams, -90 .. 90 deg (step 1 deg)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("skipped messages:   TRUEPOS x 1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("note:               1 PARAM lines read as `PARAM name value ipc_timestamp host "
                       "logger_timestamp`\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("warning:            PARAM laser_front_laser_fov 3.14159 read as radians (180 deg)"),
            std::string::npos)
      << r.out;
  // A healthy log has no warnings and skips nothing.
  const auto intel = run("-i " + kIntel);
  ASSERT_EQ(intel.status, 0) << intel.err;
  EXPECT_NE(intel.out.find("skipped messages:   none\n"), std::string::npos) << intel.out;
  EXPECT_EQ(intel.out.find("warning:"), std::string::npos) << intel.out;
}
