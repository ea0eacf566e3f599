// gridtopo-experiment end to end on config-ini/experiments/quick.ini (the first 600 scans of the Intel log, 8
// particles, informed vs odometry proposal, seeds 1-2): every run recorded and scored, the run's options.ini
// reproduces its trajectory with gridtopo-slam, the scores equal gridtopo-eval's on the same relations, --collect
// rebuilds the same tables, a second call skips every run, and the job emitters write one task per run.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/run_app.h"
#include "experiment/experiment_files.h"
#include "gridtopo/eval/relations.h"
#include "gridtopo/core/ini_file.h"
#include "gridtopo/experiment/run_scoring.h"
#include "gridtopo/io/trajectory_io.h"

namespace fs = std::filesystem;
using gridtopo::testing_app::runApp;
using namespace gridtopo;

namespace {
const std::string kQuick = std::string(GRIDTOPO_SOURCE_DIR) + "/config-ini/experiments/quick.ini";
const std::string kIntel = std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.clf.gz";
const std::string kIntelRelations = std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.relations.gz";

std::vector<nlohmann::json> jsonLines(const fs::path& p) {
  std::istringstream in(test::readText(p));
  std::vector<nlohmann::json> out;
  std::string line;
  while (std::getline(in, line)) out.push_back(nlohmann::json::parse(line));
  return out;
}
}  // namespace

TEST(ExperimentApp, QuickExperimentEndToEnd) {
  const fs::path out = test::scratch("quick");
  const auto r = runApp("gridtopo-experiment", kQuick + " -o " + out.string() + " -j 2");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("4 of 4 runs recorded (0 failed)"), std::string::npos) << r.output;
  const auto rows = jsonLines(out / "results.jsonl");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(test::countLines(test::readText(out / "results.csv")), 5u);
  for (const auto& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row.dump();
    EXPECT_EQ(row["params"]["max_scans"], "600");
    EXPECT_EQ(row["options"]["particles"], "8");
    EXPECT_EQ(row["relations_scored"].get<int>(), 47);  // the Intel relations within its first 600 scans
    EXPECT_GT(row["steps"].get<int>(), 50);
    EXPECT_GT(row["cpu_s"].get<double>(), 0.1);
    EXPECT_GT(row["peak_rss_mb"].get<double>(), 10.0);
  }
  // The informed proposal succeeds (< 5 cm) on this slice; plain odometry sampling is worse on every seed.
  for (int i : {0, 1}) {
    EXPECT_EQ(rows[i]["options"]["proposal"], "informed");
    EXPECT_LT(rows[i]["trans_mean_m"].get<double>(), 0.03) << rows[i].dump();
    EXPECT_EQ(rows[i]["success"], true);
    EXPECT_GT(rows[i + 2]["trans_mean_m"].get<double>(), rows[i]["trans_mean_m"].get<double>());
  }
  for (const char* f : {"summary.md", "plots/by_particles.dat", "plots/error_vs_particles.gp",
                        "plots/error_vs_particles.png", "plots/error_vs_particles.svg", "plots/success_vs_particles.png",
                        "plots/time_vs_particles.png", "plots/time_vs_particles.svg", "plots/neff/intel_informed.gp",
                        "plots/neff/intel_informed.png", "plots/neff/intel_odometry.svg"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
  EXPECT_GT(fs::file_size(out / "plots/error_vs_particles.png"), 5000u);
  // N_eff plot data: one block per seed, one line per processed step (stats.txt's rows).
  const std::string neff = test::readText(out / "plots/neff/intel_informed.dat");
  EXPECT_EQ(test::countLines(neff), rows[0]["steps"].get<std::size_t>() + rows[1]["steps"].get<std::size_t>() + 4u);
  EXPECT_NE(test::readText(out / "summary.md").find("| intel | informed | 2 | 0 |"), std::string::npos);

  // The run's options.ini is a RUN.ini that gridtopo-slam runs alone (here into another folder): same trajectory,
  // byte for byte. gridtopo-slam's own options.ini in RUN/out is the same RUN.ini without the comment header.
  const fs::path run0 = rows[0]["dir"].get<std::string>();
  const fs::path again = out / "again";
  const std::string run_ini = test::readText(run0 / "options.ini");
  EXPECT_EQ(run_ini.substr(run_ini.find("\n[slam_run]\n") + 1), test::readText(run0 / "out/options.ini"));
  EXPECT_NE(run_ini.find("[slam_run]\ninput = " + kIntel + "\noutput = " + (run0 / "out").string() +
                         "\nmax_scans = 600\n"),
            std::string::npos)
      << run_ini;
  EXPECT_NE(run_ini.find("/gridtopo-slam " + (run0 / "options.ini").string() + " -q\n"), std::string::npos) << run_ini;
  const auto slam = runApp("gridtopo-slam", (run0 / "options.ini").string() + " -o " + again.string() + " -q");
  ASSERT_EQ(slam.status, 0) << slam.output;
  EXPECT_EQ(test::readText(again / "trajectory.txt"), test::readText(run0 / "out/trajectory.txt"));
  auto slamSection = [](const fs::path& p) {
    std::vector<std::pair<std::string, std::string>> kv;
    const auto doc = IniFile::read(p.string());
    for (const auto& key : doc.keys("slam")) kv.emplace_back(key, *doc.value("slam", key));
    return kv;
  };
  EXPECT_EQ(slamSection(run0 / "options.ini"), slamSection(again / "options.ini"));
  EXPECT_GT(slamSection(run0 / "options.ini").size(), 60u);

  // The scores are gridtopo-eval's on the relations within the run's span.
  const auto traj = io::readTrajectory((run0 / "out/trajectory.txt").string());
  const auto within = experiment::relationsWithin(eval::readRelations(kIntelRelations), traj);
  EXPECT_EQ(within.size(), rows[0]["relations_scored"].get<std::size_t>());
  std::ostringstream rel;
  rel.precision(17);
  for (const auto& x : within)
    rel << x.t1 << ' ' << x.t2 << ' ' << x.delta.x << ' ' << x.delta.y << " 0 0 0 " << x.delta.phi << "\n";
  test::writeText(out / "within.relations", rel.str());
  const auto ev = runApp("gridtopo-eval", "-r " + (out / "within.relations").string() + " -l " + kIntel + " -t " +
                                              (run0 / "out/trajectory.txt").string() + " -j " +
                                              (out / "eval.json").string());
  ASSERT_EQ(ev.status, 0) << ev.output;
  const auto ej = nlohmann::json::parse(test::readText(out / "eval.json"));
  EXPECT_NEAR(ej["translational_m"]["mean"].get<double>(), rows[0]["trans_mean_m"].get<double>(), 1e-12);
  EXPECT_NEAR(ej["rotational_deg"]["max"].get<double>(), rows[0]["rot_max_deg"].get<double>(), 1e-9);

  // --collect rebuilds the same tables from the records; a second run skips every run.
  const std::string csv = test::readText(out / "results.csv");
  fs::remove(out / "results.csv");
  const auto c = runApp("gridtopo-experiment", kQuick + " -o " + out.string() + " --collect");
  ASSERT_EQ(c.status, 0) << c.output;
  EXPECT_EQ(test::readText(out / "results.csv"), csv);
  const auto second = runApp("gridtopo-experiment", kQuick + " -o " + out.string() + " -q");
  EXPECT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(test::readText(out / "results.csv"), csv);

  // Jobs for a scheduler: one Slurm array task / one GNU parallel line per run.
  const auto s = runApp("gridtopo-experiment", kQuick + " -o " + out.string() + " --emit slurm");
  ASSERT_EQ(s.status, 0) << s.output;
  const std::string script = test::readText(out / "slurm.sh");
  EXPECT_NE(script.find("#SBATCH --array=0-3\n"), std::string::npos) << script;
  EXPECT_NE(script.find("--run-index \"$SLURM_ARRAY_TASK_ID\""), std::string::npos) << script;
  EXPECT_NE(script.find(" -o " + out.string()), std::string::npos) << script;
  const auto p = runApp("gridtopo-experiment", kQuick + " -o " + out.string() + " --emit parallel");
  ASSERT_EQ(p.status, 0) << p.output;
  const std::string jobs = test::readText(out / "parallel.jobs");
  EXPECT_EQ(test::countLines(jobs), 4u);
  EXPECT_NE(jobs.find("quick.ini -o " + out.string() + " --run-index 3\n"), std::string::npos) << jobs;
}

TEST(ExperimentApp, BadIniStopsBeforeAnythingRuns) {
  const fs::path dir = test::scratch("bad");
  test::writeText(dir / "exp.ini", "[experiment]\noutput = out\n[dataset.intel]\nlog = " + kIntel +
                                       "\n[sweep]\nparticles = 4 0\n");
  const auto r = runApp("gridtopo-experiment", (dir / "exp.ini").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("gridtopo-experiment: error: " + (dir / "exp.ini").string() + ":6: [sweep] particles: "),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  const auto u = runApp("gridtopo-experiment", (dir / "exp.ini").string() + " --collect --emit slurm");
  EXPECT_EQ(u.status, 2) << u.output;
  const auto missing = runApp("gridtopo-experiment", (dir / "nothing.ini").string());
  EXPECT_EQ(missing.status, 1) << missing.output;
  EXPECT_NE(missing.output.find("nothing.ini: cannot read the INI file"), std::string::npos) << missing.output;
}
