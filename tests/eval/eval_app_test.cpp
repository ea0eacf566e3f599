// The gridtopo-eval command line: help, the reference figures through the app, JSON output, and errors.
#include <gtest/gtest.h>

#include "common/scratch.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

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

TEST(EvalApp, TheRunsLoopClosureSummaryFromTheStatsBesideTheTrajectory) {
  // gridtopo-slam writes trajectory.txt and stats.txt into one folder: the score comes with what the loop closure
  // did (text and JSON); a malformed summary line is refused with its file and line; no stats.txt, no summary.
  const fs::path dir = tmp("lc_run");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path rel = dir / "r.relations", traj = dir / "trajectory.txt", json = dir / "e.json",
                 stats = dir / "stats.txt";
  std::ofstream(rel) << "0 10 1.1 0 0 0 0 0\n0 100 0 2 0 0 0 0\n";
  std::ofstream(traj) << "0 0 0 0\n10 1 0 0\n100 0 0 0\n";
  auto r = run("-r " + rel.string() + " -t " + traj.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("loop closure"), std::string::npos) << r.output;
  std::ofstream(stats) << "# step scan_index timestamp\n0 0 0\n"
                       << "# loop_closure: nodes 1963 searches 1193 closures 168 rejected 2 ambiguous 12 on_border 3 "
                          "suspect_steps 27 optimisations 51 feedbacks 0 global_searches 515 global_refuted 7 global_proposed 32 "
                          "global_followed 5 "
                          "global_accepted 28 global_contradicted 4 global_dropped 1 largest_correction_xy 95.66 "
                          "largest_correction_theta 0.6816\n";
  r = run("-r " + rel.string() + " -t " + traj.string() + " --json " + json.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("loop closure (" + stats.string() +
                          "): 168 accepted (28 global), 2 switched off, largest correction 95.66 m / 0.6816 rad; "
                          "global search: 515 searches, 7 refuted by what the place saw, 32 proposed (5 followed), 4 "
                          "contradicted, 1 dropped\n"),
            std::string::npos)
      << r.output;
  const std::string j = slurp(json);
  EXPECT_NE(j.find("\"loop_closure_closures\": 168,"), std::string::npos) << j;
  EXPECT_NE(j.find("\"loop_closure_largest_correction_xy\": 95.66,"), std::string::npos) << j;
  std::ofstream(stats) << "# step scan_index timestamp\n0 0 0\n# loop_closure: nodes 10 closures x7\n";
  r = run("-r " + rel.string() + " -t " + traj.string() + " --json " + json.string() + "2");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(stats.string() + ":3: closures: expected a number, found 'x7'"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(json.string() + "2"));
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

// issue 36: the -c INI: unknown keys and sections refused with file and line, [relations_metric] required, a
// binary file refused up front (no MRPT backtrace).
TEST(EvalApp, OptionsFileTyposAndBinaryFilesAreRefused) {
  const fs::path ini = tmp("typo.ini");
  const std::string base = "--relations " + data("intel.relations.gz") + " -t " + ini.string() + " -c ";
  std::ofstream(ini) << "[relations_metric]\nmax_time_gapp = 3\n";
  auto r = run(base + ini.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(ini.string() + ":2: [relations_metric] max_time_gapp: unknown key (did you mean "
                                         "'max_time_gap'?"),
            std::string::npos)
      << r.output;
  std::ofstream(ini) << "[relations_metrics]\nmax_time_gap = 3\n";
  r = run(base + ini.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(ini.string() + ":1: [relations_metrics]: unknown section (did you mean [relations_metric]?"),
            std::string::npos)
      << r.output;
  std::ofstream(ini) << "[slam]\nparticles = 3\n";
  r = run(base + ini.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(ini.string() + ": [relations_metric]: section not found"), std::string::npos) << r.output;
  r = run(base + GRIDTOPO_BIN_DIR + "/gridtopo-eval");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, std::string("gridtopo-eval: error: ") + GRIDTOPO_BIN_DIR +
                          "/gridtopo-eval: not a text INI file (byte 0 is 0x7F)\n");
}

namespace {
// The Intel log's laser-line odometry as a trajectory file (the first `n` poses; 0: all).
fs::path intelOdometryTrajectory(std::size_t n, const std::string& name) {
  const auto log = gridtopo::io::readCarmenLog(data("intel.clf.gz"));
  std::vector<gridtopo::TimedPose> traj;
  for (const auto& s : log.scans)
    if (n == 0 || traj.size() < n) traj.push_back({s.scan.timestamp, s.odometry});
  const fs::path t = tmp(name);
  gridtopo::io::writeTrajectory(t.string(), traj);
  return t;
}
std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}
}  // namespace

// issue 36: inputs that do not belong together are refused with a non-zero exit, not scored. ACES relations
// against the Intel estimate: no overlap in time. A 199-pose Intel trajectory against all of Intel's relations:
// most relations outside (scored with --partial, the skipped ones counted). The -l log of another run.
TEST(EvalApp, MismatchedInputsAreRefused) {
  auto r = run("--relations " + data("aces.relations.gz") + " --log " + data("intel.clf.gz") + " --gfs " +
               data("intel.gfs.log.gz") + " --odometry laser");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("gridtopo-eval: error: " + data("aces.relations.gz") +
                          ": no relation lies in the time span ["),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("the relations and the estimate do not belong together"), std::string::npos) << r.output;

  // The first 199 poses end before the first relation begins (976052896.8 s): nothing to score, even with --partial.
  const fs::path tiny = intelOdometryTrajectory(199, "intel199.txt");
  r = run("-r " + data("intel.relations.gz") + " -t " + tiny.string() + " --partial");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(": no relation lies in the time span [976052857.33753, 976052895.965408] s of " +
                          tiny.string() + " (the relations span [976052896.784509, 976055541.107721] s)"),
            std::string::npos)
      << r.output;
  // The first 3000 poses (a fifth of the log): most relations outside, refused; --partial scores the part.
  const fs::path short_traj = intelOdometryTrajectory(3000, "intel3000.txt");
  r = run("-r " + data("intel.relations.gz") + " -t " + short_traj.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(" of 2984 relations lie outside the time span"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--partial scores the part"), std::string::npos) << r.output;
  const fs::path json = tmp("partial.json");
  r = run("-r " + data("intel.relations.gz") + " -t " + short_traj.string() + " --partial -j " + json.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string j = slurp(json);
  const auto number = [&](const std::string& key) {
    const auto p = j.find("\"" + key + "\": ");
    return p == std::string::npos ? -1.0 : std::stod(j.substr(p + key.size() + 4));
  };
  EXPECT_EQ(number("relations_total"), 2984);
  EXPECT_GT(number("relations_scored"), 0);
  EXPECT_GT(number("relations_skipped"), 2984 / 2);
  EXPECT_EQ(number("relations_scored") + number("relations_skipped"), 2984);
  EXPECT_EQ(number("estimated_poses"), 3000);
  EXPECT_NE(r.output.find("relations scored: " + std::to_string(static_cast<int>(number("relations_scored"))) +
                          " of 2984 (0 corrected by odometry, " +
                          std::to_string(static_cast<int>(number("relations_skipped"))) + " skipped"),
            std::string::npos)
      << r.output;

  const fs::path full = intelOdometryTrajectory(0, "intel_all.txt");
  r = run("-r " + data("aces.relations.gz") + " -t " + full.string() + " -l " + data("aces.clf.gz"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("gridtopo-eval: error: " + data("aces.clf.gz") + ": its times ["), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("the trajectory was made from another log"), std::string::npos) << r.output;
}

// issue 36 item 8: eval.json has every key once and its counts as numbers; scored + skipped = the file's relations.
TEST(EvalApp, JsonKeysOnceAndNumbersAsNumbers) {
  const fs::path json = tmp("keys.json");
  const auto r = run("--relations " + data("intel.relations.gz") + " --log " + data("intel.clf.gz") + " --gfs " +
                     data("intel.gfs.log.gz") + " --odometry laser --max-gap 0.25 --json " + json.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string j = slurp(json);
  for (const char* key : {"\"max_time_gap_s\": 0.25,", "\"estimated_poses\": 910,", "\"relations_total\": 2984,",
                          "\"relations_scored\": 2984,", "\"relations_skipped\": 0,", "\"largest_time_gap_s\": "})
    EXPECT_EQ(occurrences(j, key), 1u) << key << "\n" << j;
  // Every top-level key once.
  std::vector<std::string> keys;
  std::istringstream lines(j);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("  \"", 0) == 0) keys.push_back(line.substr(2, line.find("\":") - 1));
  std::vector<std::string> sorted = keys;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << j;
  EXPECT_GT(keys.size(), 15u);
  EXPECT_NE(r.output.find("relations scored: 2984 of 2984 ("), std::string::npos) << r.output;
  // Yes/no options as JSON booleans, never as the strings "true" / "false".
  EXPECT_EQ(occurrences(j, "\"odometry_interpolated\": false,"), 1u) << j;
  EXPECT_EQ(occurrences(j, "\"estimate_interpolated\": false,"), 1u) << j;
  EXPECT_EQ(occurrences(j, "\"true\""), 0u) << j;
  EXPECT_EQ(occurrences(j, "\"false\""), 0u) << j;
}
