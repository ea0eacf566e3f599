// One gridtopo-eval run as a library call: the estimate checks, the flags over the INI options, the run on small
// files and its text, warnings and outputs.
#include "gridtopo/eval/relations_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

#include "common/scratch.h"
#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"

using namespace gridtopo;
using namespace gridtopo::eval;

TEST(RelationsRun, ExactlyOneEstimateAndTheRawLogForGfsAndBaseline) {
  RelationsRunSpec s;
  s.relations = "r";
  EXPECT_THROW(checkRelationsRunSpec(s), UsageError);  // none
  s.trajectory = "t";
  EXPECT_NO_THROW(checkRelationsRunSpec(s));
  s.baseline_odometry = true;
  EXPECT_THROW(checkRelationsRunSpec(s), UsageError);  // two
  s.trajectory.clear();
  EXPECT_THROW(checkRelationsRunSpec(s), UsageError);  // baseline without --log
  s.log = "l";
  EXPECT_NO_THROW(checkRelationsRunSpec(s));
}

TEST(RelationsRun, FlagsOverrideTheIniAndNameTheBadOne) {
  RelationsRunSpec s;
  s.metric.max_time_gap = 0.5;
  s.metric.interpolate_odometry = true;
  RelationsFlags f;
  applyRelationsFlags(s, f);  // nothing given: the INI's values stay
  EXPECT_EQ(s.metric.max_time_gap, 0.5);
  EXPECT_TRUE(s.metric.interpolate_odometry);
  EXPECT_EQ(s.corrected.match, CorrectedTimeMatch::Auto);
  f.odometry = "odom", f.gfs_match = "ranges", f.gfs_pose = "laser", f.max_gap = 0.2, f.interpolate_estimate = true;
  applyRelationsFlags(s, f);
  EXPECT_EQ(s.metric.odometry, OdometrySource::OdomLines);
  EXPECT_EQ(s.metric.max_time_gap, 0.2);
  EXPECT_TRUE(s.metric.interpolate_estimate);
  EXPECT_EQ(s.corrected.match, CorrectedTimeMatch::LoggerAndRanges);
  EXPECT_EQ(s.corrected.pose, CorrectedPose::Laser);
  const auto usage = [&](RelationsFlags bad) {
    try {
      applyRelationsFlags(s, bad);
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  RelationsFlags b;
  b.odometry = "wheels";
  EXPECT_EQ(usage(b).rfind("--odometry: ", 0), 0u);
  b = {}, b.max_gap = -1;
  EXPECT_EQ(usage(b), "--max-gap must be >= 0");
  b = {}, b.gfs_pose = "head";
  EXPECT_EQ(usage(b), "--gfs-pose must be robot or laser");
}

TEST(RelationsRun, RevisitSpanFlagOverridesTheIniAndMustBePositive) {
  RelationsRunSpec s;
  s.metric.revisit_span = 30.0;  // as from an INI
  applyRelationsFlags(s, {});
  EXPECT_EQ(s.metric.revisit_span, 30.0);
  RelationsFlags f;
  f.revisit_span = 7.5;
  applyRelationsFlags(s, f);
  EXPECT_EQ(s.metric.revisit_span, 7.5);
  for (const double bad : {0.0, -1.0, std::nan("")}) {
    f.revisit_span = bad;
    try {
      applyRelationsFlags(s, f);
      ADD_FAILURE() << "--revisit-span " << bad << " accepted";
    } catch (const UsageError& e) {
      EXPECT_EQ(std::string(e.what()), "--revisit-span must be > 0");
    }
  }
  EXPECT_EQ(s.metric.revisit_span, 7.5);
}

TEST(RelationsRun, TextAndJsonSplitLocalAndRevisitRelations) {
  const auto d = test::scratch("relations_run_split");
  const std::string rel = (d / "rel.txt").string(), traj = (d / "traj.txt").string();
  // Poses at t = 0, 10 and 100 (back at the start). Two local relations (10 s) with 0.1 and 0.3 m error, one
  // revisit (100 s) with 2 m error.
  std::ofstream(rel) << "0 10 1.1 0 0 0 0 0\n10 0 -1.3 0 0 0 0 0\n0 100 0 2 0 0 0 0\n";
  std::ofstream(traj) << "0 0 0 0\n10 1 0 0\n100 0 0 0\n";
  RelationsRunSpec s;
  s.relations = rel, s.trajectory = traj;
  std::ostringstream log;
  RelationsRun run = runRelations(s, log);
  EXPECT_NEAR(run.result.local.translational.mean, 0.2, 1e-12);
  EXPECT_NEAR(run.result.revisit.translational.mean, 2.0, 1e-12);
  std::string text = relationsRunText(run);
  EXPECT_NE(text.find("\nlocal (|t2-t1| <= 50 s): 0.2000 m (n=2), 0.00 deg; revisits (> 50 s): 2.0000 m (n=1), "
                      "0.00 deg\n"),
            std::string::npos)
      << text;
  OutputSet out;
  stageRelationsOutputs(out, run, (d / "split.json").string(), "");
  out.commit();
  std::ifstream jf(d / "split.json");
  const std::string json((std::istreambuf_iterator<char>(jf)), {});
  EXPECT_NE(json.find("  \"revisit_span_s\": 50,\n"), std::string::npos) << json;
  EXPECT_NE(json.find("  \"local\": {\"count\": 2, \"translational_m\": {\"mean\": 0.2"), std::string::npos) << json;
  EXPECT_NE(json.find("  \"revisit\": {\"count\": 1, \"translational_m\": {\"mean\": 2,"), std::string::npos)
      << json;
  // A span of 5 s makes every relation a revisit.
  RelationsFlags f;
  f.revisit_span = 5.0;
  applyRelationsFlags(s, f);
  run = runRelations(s, log);
  text = relationsRunText(run);
  EXPECT_NE(text.find("\nlocal (|t2-t1| <= 5 s): none (n=0); revisits (> 5 s): 0.8000 m (n=3), 0.00 deg\n"),
            std::string::npos)
      << text;
}

TEST(RelationsRun, ScoresATrajectoryFileAndWritesBothOutputs) {
  const auto d = test::scratch("relations_run");
  const std::string rel = (d / "rel.txt").string(), traj = (d / "traj.txt").string();
  // Two relations between the poses at t = 1 and t = 2: the first says 1 m ahead (the estimate's 1 m: no error),
  // the second 1.5 m ahead (0.5 m translational error).
  std::ofstream(rel) << "1 2 1 0 0 0 0 0\n1 2 1.5 0 0 0 0 0\n";
  std::ofstream(traj) << "1 0 0 0\n2 1 0 0\n";
  RelationsRunSpec s;
  s.relations = rel, s.trajectory = traj;
  std::ostringstream log;
  const RelationsRun run = runRelations(s, log);
  EXPECT_EQ(run.relation_count, 2u);
  EXPECT_DOUBLE_EQ(run.result.translational.mean, 0.25);
  EXPECT_EQ(log.str(), "");
  const std::string text = relationsRunText(run);
  EXPECT_EQ(text.rfind("relations:  " + rel + " (2)\nodometry: none\nodometry_interpolated: false\n", 0), 0u) << text;
  EXPECT_NE(text.find("estimated_poses: 2\n"), std::string::npos);
  EXPECT_EQ(relationsRunWarnings(run), "");
  OutputSet out;
  stageRelationsOutputs(out, run, (d / "e.json").string(), (d / "e.txt").string());
  out.commit();
  EXPECT_TRUE(std::filesystem::is_regular_file(d / "e.json"));
  EXPECT_TRUE(std::filesystem::is_regular_file(d / "e.txt"));
  // An empty trajectory is bad input naming the file.
  std::ofstream(traj) << "# nothing\n";
  try {
    runRelations(s, log);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), traj);
  }
}
