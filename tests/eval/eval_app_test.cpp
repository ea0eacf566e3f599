// The gridtopo-eval command line: help, the reference figures through the app, JSON output, and errors.
#include <gtest/gtest.h>

#include "common/scratch.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include "common/run_app.h"
#include "gridtopo/io/carmen_log.h"
#include "gridtopo/io/trajectory_io.h"

namespace fs = std::filesystem;

namespace {
using Run = gridtopo::testing_app::AppRun;
Run run(const std::string& args) { return gridtopo::testing_app::runApp("gridtopo-eval", args); }
std::string data(const std::string& f) { return std::string(GRIDTOPO_DATA_DIR) + "/slam/" + f; }
fs::path tmp(const std::string& name) { return gridtopo::test::scratchPath("eval_app_" + name); }
std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  return std::string(std::istreambuf_iterator<char>(f), {});
}
}  // namespace

TEST(EvalApp, Help) {
  const auto r = run("--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("--relations"), std::string::npos);
  EXPECT_NE(r.output.find("--interpolate"), std::string::npos);
}

TEST(EvalApp, GmappingReferenceWithJson) {
  const fs::path json = tmp("gfs.json");
  fs::remove(json);
  const auto r = run("--relations " + data("intel.relations.gz") + " --log " + data("intel.clf.gz") + " --gfs " +
                     data("intel.gfs.log.gz") + " --odometry laser --json " + json.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("translational error:   0.0606 ± 0.0778 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("rotational error:      2.387 ± 3.297 deg"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\nlocal (|t2-t1| <= 50 s): 0.0589 m (n=1773), 2.47 deg; revisits (> 50 s): 0.0631 m "
                          "(n=1211), 2.27 deg\n"),
            std::string::npos)
      << r.output;
  const std::string j = slurp(json);
  EXPECT_NE(j.find("\"translational_m\": {\"mean\": 0.0606"), std::string::npos) << j;
  EXPECT_NE(j.find("\"count\": 2984"), std::string::npos);
  EXPECT_NE(j.find("\"odometry\": \"laser\""), std::string::npos);
  EXPECT_NE(j.find("\"gfs_time_match\": \"logger\""), std::string::npos);
}

TEST(EvalApp, ShuffledTrajectoryFileEqualsBaseline) {
  const auto log = gridtopo::io::readCarmenLog(data("intel.clf.gz"));
  std::vector<gridtopo::TimedPose> traj;
  for (const auto& s : log.scans) traj.push_back({s.scan.timestamp, s.odometry});
  std::mt19937 rng(7);
  std::shuffle(traj.begin(), traj.end(), rng);
  const fs::path t = tmp("odometry_traj.txt");
  gridtopo::io::writeTrajectory(t.string(), traj);
  const fs::path errors = tmp("errors.txt");
  const auto a = run("-r " + data("intel.relations.gz") + " -t " + t.string() + " -e " + errors.string());
  ASSERT_EQ(a.status, 0) << a.output;
  EXPECT_NE(a.output.find("translational error:   7.3702 ± 14.3515 m"), std::string::npos) << a.output;
  const auto b = run("-r " + data("intel.relations.gz") + " -l " + data("intel.clf.gz") + " --baseline-odometry");
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_NE(b.output.find("translational error:   7.3702 ± 14.3515 m"), std::string::npos) << b.output;
  const std::string e = slurp(errors);
  EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 2985);
}

TEST(EvalApp, LocalAndRevisitSplitWithTheRevisitSpanFlagAndJson) {
  const fs::path rel = tmp("split.relations"), traj = tmp("split_traj.txt"), json = tmp("split.json");
  // Two local relations (10 s) with 0.1 and 0.3 m error, one revisit (100 s) with 2 m error.
  std::ofstream(rel) << "0 10 1.1 0 0 0 0 0\n10 0 -1.3 0 0 0 0 0\n0 100 0 2 0 0 0 0\n";
  std::ofstream(traj) << "0 0 0 0\n10 1 0 0\n100 0 0 0\n";
  auto r = run("-r " + rel.string() + " -t " + traj.string() + " --json " + json.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("local (|t2-t1| <= 50 s): 0.2000 m (n=2), 0.00 deg; revisits (> 50 s): 2.0000 m (n=1)"),
            std::string::npos)
      << r.output;
  EXPECT_NE(slurp(json).find("\"revisit_span_s\": 50,"), std::string::npos);
  r = run("-r " + rel.string() + " -t " + traj.string() + " --revisit-span 200 --json " + json.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("local (|t2-t1| <= 200 s): 0.8000 m (n=3), 0.00 deg; revisits (> 200 s): none (n=0)"),
            std::string::npos)
      << r.output;
  EXPECT_NE(slurp(json).find("\"revisit_span_s\": 200,"), std::string::npos);
  r = run("-r " + rel.string() + " -t " + traj.string() + " --revisit-span 0");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--revisit-span must be > 0"), std::string::npos) << r.output;
}

TEST(EvalApp, BadInputGivesFileLineFieldAndNonZeroExit) {
  const fs::path rel = tmp("bad.relations");
  std::ofstream(rel) << "1 2 3 4 0 0 0 0.1\n1 2 3 4 0 0 0 0.1\n1 2 3 nan 0 0 0 0.1\n";
  const fs::path traj = tmp("traj.txt");
  std::ofstream(traj) << "1 0 0 0\n2 1 0 0\n";
  auto r = run("-r " + rel.string() + " -t " + traj.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(rel.string() + ":3: y: not a finite number"), std::string::npos) << r.output;

  std::ofstream(traj) << "1 0 0 0\n2 1 x 0\n";
  std::ofstream(rel) << "1 2 1 0 0 0 0 0\n";
  r = run("-r " + rel.string() + " -t " + traj.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(traj.string() + ":2: y:"), std::string::npos) << r.output;

  const fs::path log = tmp("bad.clf");
  std::ofstream(log) << "ODOM 0 0 0 0 0 0 1 h 1\nODOM 0 0 0 0 0 0 1 h\n";
  std::ofstream(traj) << "1 0 0 0\n2 1 0 0\n";
  r = run("-r " + rel.string() + " -t " + traj.string() + " -l " + log.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(log.string() + ":2: ODOM: expected 10 tokens"), std::string::npos) << r.output;

  r = run("-r " + rel.string());  // no estimate
  EXPECT_EQ(r.status, 2);
  r = run("-r " + rel.string() + " -t " + traj.string() + " --odometry wheels");
  EXPECT_EQ(r.status, 2);
  r = run("-r /nonexistent.relations -t " + traj.string());
  EXPECT_EQ(r.status, 1);
  r = run("-r " + rel.string() + " -t " + traj.string() + " --config /nonexistent.ini");
  EXPECT_EQ(r.status, 1);
  // A good run writes its JSON; a failed run leaves none.
  const fs::path json = tmp("none.json");
  fs::remove(json);
  std::ofstream(rel) << "1 2 1 0 0 0 0 0\n1 2 1 0 0 0 0 x\n";
  r = run("-r " + rel.string() + " -t " + traj.string() + " --json " + json.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_FALSE(fs::exists(json));
}

TEST(EvalApp, IniFileSetsTheOptions) {
  const std::string ini = std::string(GRIDTOPO_SOURCE_DIR) + "/config-ini/eval.ini";
  ASSERT_TRUE(fs::exists(ini));
  const auto r = run("-r " + data("intel.relations.gz") + " -l " + data("intel.clf.gz") + " --gfs " +
                     data("intel.gfs.log.gz") + " --config " + ini);
  ASSERT_EQ(r.status, 0) << r.output;
  // The shipped INI keeps the reference settings: ODOM lines (auto), nearest reading, 0.1 s.
  EXPECT_NE(r.output.find("translational error:   0.0723 ± 0.0857 m"), std::string::npos) << r.output;
}
