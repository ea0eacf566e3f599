// Topology runs end to end on config-ini/experiments/topology_intel_plan.ini (the shipped Intel floor plan, the two
// room segmentations): each run is gridtopo-topology then gridtopo-topology-compare; the records hold exactly the
// scores of those two programs' files, the run's topology.ini reproduces its labels, and a second call skips both
// runs. A SLAM run followed by the topology of its map is planned with the SLAM run's map as the topology's input.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/run_app.h"
#include "experiment/experiment_files.h"
#include "gridtopo/experiment/run_plan.h"

namespace fs = std::filesystem;
using gridtopo::testing_app::runApp;
using namespace gridtopo;

namespace {
const std::string kSource = GRIDTOPO_SOURCE_DIR;
const std::string kData = GRIDTOPO_DATA_DIR;
const std::string kPlanIni = kSource + "/config-ini/experiments/topology_intel_plan.ini";

std::vector<nlohmann::json> jsonLines(const fs::path& p) {
  std::istringstream in(test::readText(p));
  std::vector<nlohmann::json> out;
  std::string line;
  while (std::getline(in, line)) out.push_back(nlohmann::json::parse(line));
  return out;
}

nlohmann::json readJson(const fs::path& p) { return nlohmann::json::parse(test::readText(p)); }
}  // namespace

TEST(ExperimentTopology, PlanRunsRecordTheCompareScores) {
  const fs::path out = test::scratch("plan");
  const auto r = runApp("gridtopo-experiment", kPlanIni + " -o " + out.string() + " -j 2");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("2 of 2 runs recorded (0 failed)"), std::string::npos) << r.output;
  const auto rows = jsonLines(out / "results.jsonl");
  ASSERT_EQ(rows.size(), 2u);
  const char* segmentation[] = {"regions", "doorways"};
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& row = rows[i];
    ASSERT_EQ(row["status"], "ok") << row.dump();
    EXPECT_EQ(row["params"]["topology.segmentation"], segmentation[i]);
    EXPECT_EQ(row["topology_options"]["topology.segmentation"], segmentation[i]);
    EXPECT_EQ(row["topology_options"]["topology.threads"], "1");
    EXPECT_EQ(row["relations_scored"], 0);
    EXPECT_TRUE(row["success"].is_null());
    const fs::path dir = row["dir"].get<std::string>();
    // The record's numbers are those of the run's topology.json and compare.json.
    const auto graph = readJson(dir / "topology/topology.json");
    EXPECT_EQ(row["graph_nodes"].get<std::size_t>(), graph["nodes"].size());
    EXPECT_EQ(row["graph_edges"].get<std::size_t>(), graph["edges"].size());
    const auto c = readJson(dir / "topology/compare.json");
    EXPECT_EQ(row["label_accuracy"].get<double>(), c["labels"]["accuracy"].get<double>());
    EXPECT_EQ(row["recall_room"].get<double>(), c["labels"]["recall"][0].get<double>());
    EXPECT_EQ(row["recall_corridor"].get<double>(), c["labels"]["recall"][1].get<double>());
    EXPECT_EQ(row["recall_doorway"].get<double>(), c["labels"]["recall"][2].get<double>());
    EXPECT_EQ(row["seg_recall"].get<double>(), c["segmentation"]["recall"].get<double>());
    EXPECT_EQ(row["seg_precision"].get<double>(), c["segmentation"]["precision"].get<double>());
    EXPECT_EQ(row["graph_attached"].get<double>(), c["graph"]["attached_fraction"].get<double>());
    EXPECT_EQ(row["graph_loops_closed"].get<double>(), c["graph"]["loops_closed"].get<double>());
    EXPECT_EQ(row["graph_plan_loops"].get<double>(), c["graph"]["plan_loops"].get<double>());
    EXPECT_GT(row["cpu_s"].get<double>(), 0.2);  // both processes' CPU time
  }
  // On the plan itself (measured 2026-12-02: 95.3 % of the cells, 52 nodes, 67 edges, 18 of 20 rooms attached;
  // 95.4 % since the doorways from geometry, 2026-12-03).
  EXPECT_NEAR(rows[0]["label_accuracy"].get<double>(), 0.953446, 0.01);
  EXPECT_NEAR(rows[0]["seg_recall"].get<double>(), 0.992879, 0.01);
  EXPECT_NEAR(rows[0]["graph_attached"].get<double>(), 0.9, 0.051);
  // The segmentation changes the segments, not the labels.
  EXPECT_EQ(rows[0]["label_accuracy"], rows[1]["label_accuracy"]);
  EXPECT_NE(rows[0]["seg_recall"], rows[1]["seg_recall"]);

  // The CSV carries the topology options and scores; the summary their means.
  const std::string csv = test::readText(out / "results.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  for (const char* col : {",topology.segmentation,", ",relaxation.max_iterations,", ",label_accuracy,", ",seg_recall,",
                          ",graph_nodes,", ",graph_attached,"})
    EXPECT_NE(header.find(col), std::string::npos) << col;
  EXPECT_NE(test::readText(out / "summary.md").find("| intel_plan | regions | 1 | 0 |"), std::string::npos);
  EXPECT_NE(test::readText(out / "summary.md").find("| 52.0 | 67.0 | 0.954 |"), std::string::npos)
      << test::readText(out / "summary.md");

  // The run's topology.ini is a RUN.ini gridtopo-topology runs alone: same labels, byte for byte.
  const fs::path run0 = rows[0]["dir"].get<std::string>();
  const auto t = runApp("gridtopo-topology", (run0 / "topology.ini").string() + " -o " + (out / "again").string() + " -q");
  ASSERT_EQ(t.status, 0) << t.output;
  EXPECT_EQ(test::readText(out / "again/labels.png"), test::readText(run0 / "topology/labels.png"));

  // A second call skips both runs and writes the same table.
  const auto second = runApp("gridtopo-experiment", kPlanIni + " -o " + out.string() + " -q");
  EXPECT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(test::readText(out / "results.csv"), csv);
}

TEST(ExperimentTopology, ASlamRunsTopologyReadsItsMap) {
  const fs::path dir = test::scratch("slam");
  test::writeText(dir / "exp.ini",
                  "[experiment]\noutput = out\ntopology_ini = " + kSource + "/config-ini/topology.ini\nplaces_model = " +
                      kData + "/models/places_model.yml\n[dataset.intel]\nlog = " + kData + "/slam/intel.clf.gz\nrelations = " + kData +
                      "/slam/intel.relations.gz\nplan = " +
                      kData + "/places/maps/lab_intel.png\nplan_labels = " + kData +
                      "/places/labelled/training_intel.png\nplan_segmentation = " + kData +
                      "/places/groundtruth/lab_intel_gt_segmentation.png\n[sweep]\nmax_scans = 600\nseed = 1 2\n");
  const auto plan = experiment::planExperiment(experiment::loadExperimentSpec((dir / "exp.ini").string()));
  ASSERT_EQ(plan.runs.size(), 2u);
  const auto& run = plan.runs[1];
  EXPECT_TRUE(run.slam);
  EXPECT_TRUE(run.topology);
  EXPECT_EQ(run.map, (fs::path(run.dir) / "out/map.yaml").string());
  const auto stages = experiment::runStages(run, {"S", "T", "C"});
  ASSERT_EQ(stages.size(), 3u);
  EXPECT_EQ(stages[0].argv, (std::vector<std::string>{"S", run.dir + "/options.ini", "-q"}));
  EXPECT_EQ(stages[1].argv, (std::vector<std::string>{"T", run.dir + "/topology.ini", "-q"}));
  EXPECT_EQ(stages[2].argv,
            (std::vector<std::string>{"C", run.dir + "/out/map.yaml", run.dir + "/topology", "-c",
                                      run.dir + "/topology/options.ini", "--reference-map",
                                      kData + "/places/maps/lab_intel.png", "--reference-labels",
                                      kData + "/places/labelled/training_intel.png", "--reference-segmentation",
                                      kData + "/places/groundtruth/lab_intel_gt_segmentation.png", "-j",
                                      run.dir + "/topology/compare.json", "-t", run.dir + "/out/trajectory.txt"}));
  EXPECT_EQ(stages[2].log, run.dir + "/compare.log");
  // The topology of the run's map reads the run's trajectory (its door passages), as gridtopo-map's.
  EXPECT_NE(experiment::topologyIniText(plan, run).find("trajectory = " + run.dir + "/out/trajectory.txt"),
            std::string::npos)
      << experiment::topologyIniText(plan, run);
  // Run 0 end to end: gridtopo-slam on the first 600 scans, then the topology of its map, scored against the plan.
  const auto r = runApp("gridtopo-experiment", (dir / "exp.ini").string() + " --run-index 0 -q");
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path run0 = plan.runs[0].dir;
  const auto rec = readJson(run0 / "result.json");
  EXPECT_EQ(rec["status"], "ok") << rec.dump();
  EXPECT_EQ(rec["relations_scored"], 47);
  EXPECT_LT(rec["trans_mean_m"].get<double>(), 0.03);
  EXPECT_EQ(rec["label_accuracy"].get<double>(), readJson(run0 / "topology/compare.json")["labels"]["accuracy"].get<double>());
  EXPECT_TRUE(readJson(run0 / "topology/compare.json")["trajectory"]["has_trajectory"].get<bool>());
  EXPECT_EQ(rec["graph_nodes"].get<std::size_t>(), readJson(run0 / "topology/topology.json")["nodes"].size());
  EXPECT_GT(rec["graph_nodes"].get<std::size_t>(), 0u);
  EXPECT_TRUE(fs::is_regular_file(run0 / "out/map.yaml"));  // keep_maps defaults to true
  const std::string ini = experiment::topologyIniText(plan, run);
  EXPECT_NE(ini.find("[topology_run]\nmap = " + run.dir + "/out/map.yaml\nmodel = " + kData +
                     "/models/places_model.yml\noutput = " + run.dir + "/topology\n"),
            std::string::npos)
      << ini;
  // The same SLAM run without topology has another id: the topology options and inputs are part of a run's key.
  test::writeText(dir / "slam.ini", "[experiment]\noutput = out\n[dataset.intel]\nlog = " + kData +
                                        "/slam/intel.clf.gz\nrelations = " + kData + "/slam/intel.relations.gz\n[sweep]\nmax_scans = 600\nseed = 1 2\n");
  const auto slam_only = experiment::planExperiment(experiment::loadExperimentSpec((dir / "slam.ini").string()));
  EXPECT_EQ(slam_only.runs[1].options_ini, run.options_ini);
  EXPECT_NE(slam_only.runs[1].id, run.id);
  EXPECT_FALSE(slam_only.runs[1].topology);
  EXPECT_EQ(experiment::runStages(slam_only.runs[1], {"S", "T", "C"}).size(), 1u);
}
