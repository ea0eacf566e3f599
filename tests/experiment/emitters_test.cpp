// The job emitters: a Slurm array with one task per run and the cores a run needs, a GNU parallel list with one
// command per run; paths with blanks stay one shell word.
#include "gridtopo/experiment/emitters.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "experiment/experiment_files.h"
#include "gridtopo/experiment/subprocess.h"

namespace fs = std::filesystem;
using namespace gridtopo;
using namespace gridtopo::experiment;

namespace {
ExperimentPlan plan(const std::string& threads) {
  const fs::path dir = test::scratch("emit dir");  // a blank in every path
  test::writeText(dir / "exp.ini", "[experiment]\nname = em\noutput = out\n[dataset.intel]\nlog = " +
                                       std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.clf.gz\n[sweep]\nthreads = " +
                                       threads + "\nseed = 1..3\n");
  return planExperiment(loadExperimentSpec((dir / "exp.ini").string()));
}
}  // namespace

TEST(Emitters, SlurmArrayOneTaskPerRun) {
  const ExperimentPlan p = plan("2");
  const std::string s = slurmScript(p, "/opt/gt/gridtopo-experiment", "/data/my exp.ini");
  EXPECT_EQ(s.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(s.find("#SBATCH --array=0-2\n"), std::string::npos) << s;
  EXPECT_NE(s.find("#SBATCH --cpus-per-task=2\n"), std::string::npos) << s;
  EXPECT_NE(s.find("#SBATCH --job-name=em\n"), std::string::npos) << s;
  EXPECT_NE(s.find("exec /opt/gt/gridtopo-experiment '/data/my exp.ini' -o '" + p.output +
                   "' --run-index \"$SLURM_ARRAY_TASK_ID\"\n"),
            std::string::npos)
      << s;
  EXPECT_NE(plan("0").runs.size(), 0u);
  EXPECT_NE(slurmScript(plan("0"), "/x", "/y.ini").find("#SBATCH --exclusive\n"), std::string::npos);
}

TEST(Emitters, ParallelListAndFiles) {
  const ExperimentPlan p = plan("1");
  const std::string jobs = parallelJobs(p, "/opt/gt/gridtopo-experiment", "/data/e.ini");
  EXPECT_EQ(test::countLines(jobs), 3u);
  EXPECT_NE(jobs.find("/opt/gt/gridtopo-experiment /data/e.ini -o '" + p.output + "' --run-index 2\n"),
            std::string::npos)
      << jobs;
  const std::string script = emitJobs(p, "slurm", "/x", "/y.ini");
  EXPECT_EQ(script, p.output + "/slurm.sh");
  EXPECT_TRUE(fs::is_directory(p.output + "/slurm-logs"));
  EXPECT_TRUE((fs::status(script).permissions() & fs::perms::owner_exec) != fs::perms::none);
  EXPECT_EQ(emitJobs(p, "parallel", "/x", "/y.ini"), p.output + "/parallel.jobs");
  EXPECT_THROW(emitJobs(p, "pbs", "/x", "/y.ini"), std::invalid_argument);
  EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
  EXPECT_EQ(shellQuote("plain-1.ini"), "plain-1.ini");
}
