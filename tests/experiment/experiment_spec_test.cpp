// Reading and checking an experiment INI: good files plan the expected runs; every bad file stops before anything
// runs with an error naming the file, the line and "[section] key".
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>

#include "experiment/experiment_files.h"
#include "gridtopo/core/error.h"
#include "gridtopo/experiment/run_plan.h"
#include "gridtopo/slam/slam_options.h"

namespace fs = std::filesystem;
using namespace gridtopo;
using namespace gridtopo::experiment;

namespace {

const std::string kData = GRIDTOPO_DATA_DIR;

/// An experiment INI in a fresh folder with `body` after a [dataset.intel] section.
fs::path experimentIni(const std::string& name, const std::string& body) {
  const fs::path dir = test::scratch(name);
  const fs::path ini = dir / "exp.ini";
  test::writeText(ini, "[experiment]\nname = t\noutput = out\n\n[dataset.intel]\nlog = " + kData +
                           "/slam/intel.clf.gz\nrelations = " + kData + "/slam/intel.relations.gz\n\n" + body);
  return ini;
}

/// The what() of the InputError that loading and planning `ini` throws, or "accepted".
std::string errorOf(const fs::path& ini) {
  try {
    planExperiment(loadExperimentSpec(ini.string()));
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(ExperimentSpec, PlansTheProductWithOptionsLoadableBySlamOptions) {
  const fs::path ini = experimentIni("good", "[slam]\nthreads = 1\n\n[sweep]\nmax_scans = 100\n"
                                             "proposal = informed mode-only\nparticles = 4 8\nseed = 1..3\n");
  const ExperimentPlan plan = planExperiment(loadExperimentSpec(ini.string()));
  ASSERT_EQ(plan.runs.size(), 12u);
  EXPECT_EQ(plan.output, (ini.parent_path() / "out").string());
  EXPECT_EQ(plan.varied_keys, (std::vector<std::string>{"dataset", "proposal", "particles", "seed"}));
  const PlannedRun& r = plan.runs[7];  // index = 6 proposal + 3 particles + seed: mode-only, 4, seed 2
  EXPECT_EQ(r.label, "intel_mode-only_particles-4_seed-2");
  EXPECT_EQ(r.max_scans, 100);
  EXPECT_EQ(r.threads, 1);
  EXPECT_EQ(r.log, kData + "/slam/intel.clf.gz");
  EXPECT_EQ(r.dir, plan.output + "/runs/" + r.label + "_" + r.id.substr(0, 8));
  // The run's options load back to the swept values, the fixed [slam] value and the defaults elsewhere.
  mrpt::config::CConfigFileMemory cfg(r.options_ini);
  slam::SlamOptions o;
  o.loadFromConfigFile(cfg, "slam");
  EXPECT_EQ(o.particles, 4);
  EXPECT_EQ(o.seed, 2u);
  EXPECT_EQ(o.threads, 1);
  EXPECT_EQ(o.proposal.type, slam::ProposalType::ModeOnly);
  EXPECT_DOUBLE_EQ(o.resample_threshold, slam::SlamOptions().resample_threshold);
  EXPECT_EQ(optionValue(r.options_ini, "proposal"), "mode-only");
  // Ids are distinct and stable: planning again gives the same ids.
  const ExperimentPlan again = planExperiment(loadExperimentSpec(ini.string()));
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    EXPECT_EQ(plan.runs[i].id, again.runs[i].id);
    for (std::size_t j = 0; j < i; ++j) EXPECT_NE(plan.runs[i].id, plan.runs[j].id);
  }
}

TEST(ExperimentSpec, TheIdFollowsTheInputFilesContents) {
  const fs::path dir = test::scratch("content");
  fs::copy_file(kData + "/slam/intel.relations.gz", dir / "rel.gz");
  test::writeText(dir / "exp.ini", "[experiment]\noutput = out\n[dataset.a]\nlog = " + kData +
                                       "/slam/intel.clf.gz\nrelations = rel.gz\n[sweep]\nseed = 1\n");
  const std::string before = planExperiment(loadExperimentSpec((dir / "exp.ini").string())).runs[0].id;
  test::writeText(dir / "rel.gz", "changed");
  const std::string after = planExperiment(loadExperimentSpec((dir / "exp.ini").string())).runs[0].id;
  EXPECT_NE(before, after);
}

TEST(ExperimentSpec, ZipGroupsAndImplicitDatasets) {
  const fs::path ini = experimentIni("zip", "[dataset.aces]\nlog = " + kData +
                                                "/slam/aces.clf.gz\n\n[sweep]\nparticles = 4 8\nthreads = 1 2\n"
                                                "seed = 1..2\nzip = particles threads\n");
  const ExperimentPlan plan = planExperiment(loadExperimentSpec(ini.string()));
  ASSERT_EQ(plan.runs.size(), 8u);  // 2 datasets x 2 (particles, threads) x 2 seeds
  EXPECT_EQ(plan.runs[0].dataset, "intel");
  EXPECT_EQ(plan.runs[4].dataset, "aces");
  EXPECT_EQ(plan.runs[4].relations, "");
  EXPECT_EQ(plan.runs[2].label, "intel_particles-8_threads-2_seed-1");
  EXPECT_EQ(plan.runs[2].threads, 2);
}

TEST(ExperimentSpec, BadFilesNameFileLineSectionAndKey) {
  struct Case {
    std::string body, expected;  // expected: what() after "<ini>:"
  };
  const std::vector<Case> cases = {
      {"[sweep]\nparticles = 4 8\nparticle = 3\n", "11: [sweep] particle: unknown key"},
      {"[sweep]\nresample_threshold = 0.5 2\n",
       "10: [sweep] resample_threshold: must be in [0, 1], got 2 (run 1)"},
      {"[sweep]\nproposal = informed greedy\n", "10: [sweep] proposal: must be informed, mode-only, hahnel or odometry"},
      {"[sweep]\nparticles = 4..x\n", "10: [sweep] particles: '4..x' is not a range of integers a..b"},
      {"[sweep]\ndataset = intel mit\n", "10: [sweep] dataset: no section [dataset.mit]"},
      {"[sweep]\nmax_scans = 0\n", "10: [sweep] max_scans: '0' is not a positive integer"},
      {"[sweep]\nparticles = 4 8\nseed = 1..3\nzip = particles seed\n",
       "12: [sweep] zip: zip key 'seed' has 3 values, 'particles' has 2"},
      {"[slam]\nparticles = many\n", "10: [slam] particles: cannot parse 'many' as an integer"},
      {"[slam]\nparticle = 3\n", "10: [slam] particle: unknown key"},
      {"[record]\nsuccess_metric = median\n", "10: [record] success_metric: unknown value 'median'"},
      {"[record]\nsuccess_threshold = -1\n", "10: [record] success_threshold: must be > 0"},
      {"[record]\nplots = error nef\n", "10: [record] plots: unknown plot 'nef'"},
      {"[records]\nplots = error\n", "9: [records]: unknown section"},
      {"[dataset.mit]\nlog = /nonexistent.clf\n", "10: [dataset.mit] log: no such file: /nonexistent.clf"},
      {"[dataset.mit]\nrelations = /x\n", "10: [dataset.mit] relations: no such file: /x"},
      {"[dataset.aces]\nrelations = " + kData + "/slam/aces.relations.gz\n", "9: [dataset.aces] log: missing"},
      {"[sweep]\nseed = 1\nseed = 2\n", "11: [sweep] seed: key given twice"},
      {"[sweep]\nseed 1\n", "10: seed 1: expected 'key = value'"},
  };
  for (const auto& c : cases) {
    const fs::path ini = experimentIni("bad", c.body);
    const std::string what = errorOf(ini);
    EXPECT_EQ(what.rfind(ini.string() + ":" + c.expected, 0), 0u) << "got: " << what << "\nwanted: " << c.expected;
  }
}

TEST(ExperimentSpec, BadTopologyKeysAndDatasetsAreNamed) {
  const std::string plan = "plan = " + kData + "/places/maps/lab_intel.png\nplan_labels = " + kData +
                           "/places/labelled/training_intel.png\nplan_segmentation = " + kData +
                           "/places/groundtruth/lab_intel_gt_segmentation.png\n";
  // Lines: 1 [experiment], 2 output, 3 places_model, 4 [dataset.p], 5 map, 6-8 plan, 9 the body.
  auto topologyIni = [&](const std::string& body, bool model = true) {
    const fs::path dir = test::scratch("topology");
    test::writeText(dir / "exp.ini", "[experiment]\noutput = out\n" +
                                         (model ? "places_model = " + kData + "/models/places_model.yml\n"
                                                : std::string("# no model\n")) +
                                         "[dataset.p]\nmap = " + kData + "/places/maps/lab_intel.png\n" + plan + body);
    return dir / "exp.ini";
  };
  struct Case {
    std::string body;
    bool model;
    std::string expected;  // what() after "<ini>:"
  };
  const std::vector<Case> cases = {
      {"[sweep]\ntopology.segmentaton = regions\n", true,
       "10: [sweep] topology.segmentaton: unknown key (not a topology option; see config-ini/topology.ini)"},
      {"[sweep]\ntopology.segmentation = regions rooms\n", true,
       "10: [sweep] topology.segmentation: must be regions or doorways (run 1)"},
      {"[topology]\nsegmentation = rooms\n", true, "10: [topology] segmentation: must be regions or doorways"},
      {"[relaxation]\nmax_iterations = many\n", true, "10: [relaxation] max_iterations: cannot parse 'many'"},
      {"[correction]\nno_such_rule = 1\n", true, "10: [correction] no_such_rule: unknown key (not a topology option"},
      {"[topology]\nthreads = 1\n", false, "1: [experiment] places_model: missing: topology runs need the place model"},
      {"[sweep]\nseed = 1\n", true,
       "5: [dataset.p] map: a map without a log needs topology runs (topology_ini, a [topology] section or a swept "
       "topology.KEY)"},
      {"[topology]\n[dataset.q]\nlog = " + kData + "/slam/intel.clf.gz\nmap = " + kData +
           "/places/maps/lab_intel.png\n",
       true, "12: [dataset.q] map: give a log (topology runs on the SLAM run's map) or a map, not both"},
      {"[topology]\n[dataset.q]\nmap = " + kData + "/places/maps/lab_intel.png\nplan = " + kData +
           "/places/maps/lab_intel.png\n",
       true, "10: [dataset.q] plan_labels: missing: a labelled plan needs plan, plan_labels and plan_segmentation"},
  };
  for (const auto& c : cases) {
    const fs::path ini = topologyIni(c.body, c.model);
    const std::string what = errorOf(ini);
    EXPECT_EQ(what.rfind(ini.string() + ":" + c.expected, 0), 0u) << "got: " << what << "\nwanted: " << c.expected;
  }
  // A good one: the plan's files, the map as the topology's input, the swept values in the options.
  const ExperimentPlan p =
      planExperiment(loadExperimentSpec(topologyIni("[topology]\nthreads = 1\n[sweep]\ntopology.segmentation = "
                                                    "regions doorways\nrelaxation.max_iterations = 10\n")
                                            .string()));
  ASSERT_EQ(p.runs.size(), 2u);
  EXPECT_FALSE(p.runs[1].slam);
  EXPECT_TRUE(p.runs[1].topology);
  EXPECT_EQ(p.runs[1].map, kData + "/places/maps/lab_intel.png");
  EXPECT_EQ(p.runs[1].plan_segmentation, kData + "/places/groundtruth/lab_intel_gt_segmentation.png");
  EXPECT_EQ(p.runs[1].model, kData + "/models/places_model.yml");
  EXPECT_EQ(p.runs[1].topology_options.segmentation, "doorways");
  EXPECT_EQ(p.runs[1].topology_options.relaxation.max_iterations, 10);
  EXPECT_EQ(p.runs[1].topology_options.threads, 1);
  EXPECT_EQ(p.runs[1].threads, 1);
  EXPECT_EQ(p.runs[1].label, "p_topology.segmentation-doorways");
  EXPECT_NE(p.runs[0].id, p.runs[1].id);
  EXPECT_EQ(p.varied_keys, (std::vector<std::string>{"dataset", "topology.segmentation"}));
  EXPECT_EQ(p.topology_keys.front(), "topology.threads");
}

TEST(ExperimentSpec, BadBaseIniIsNamed) {
  const fs::path dir = test::scratch("base");
  test::writeText(dir / "base.ini", "[slam]\nparticles = 30\nresolutoin = 0.05\n");
  test::writeText(dir / "exp.ini", "[experiment]\noutput = out\nbase_ini = base.ini\n[dataset.a]\nlog = " + kData +
                                       "/slam/intel.clf.gz\n");
  EXPECT_EQ(errorOf(dir / "exp.ini"), (dir / "base.ini").string() +
                                          ":3: [slam] resolutoin: unknown key (not an option of gridtopo-slam; see "
                                          "config-ini/slam.ini)");
  test::writeText(dir / "exp.ini", "[experiment]\noutput = out\nbase_ini = base.ini\nbase_section = mapping\n"
                                   "[dataset.a]\nlog = " + kData + "/slam/intel.clf.gz\n");
  EXPECT_EQ(errorOf(dir / "exp.ini"), (dir / "base.ini").string() + ": [mapping]: section not found");
  test::writeText(dir / "exp.ini", "[experiment]\nbase_ini = base.ini\n[dataset.a]\nlog = " + kData +
                                       "/slam/intel.clf.gz\n");
  test::writeText(dir / "base.ini", "[slam]\nparticles = 30\n");
  EXPECT_EQ(errorOf(dir / "exp.ini"), (dir / "exp.ini").string() +
                                          ": [experiment] output: no results folder: set output = ... or give -o");
}

TEST(ExperimentSpec, RepeatedRunsAreRefused) {
  // particles = 8 in [slam] and swept seeds listed the same way twice is impossible; two datasets with the same
  // files and a sweep over them would run identical runs.
  const fs::path ini = experimentIni("twice", "[dataset.copy]\nlog = " + kData + "/slam/intel.clf.gz\nrelations = " +
                                                  kData + "/slam/intel.relations.gz\n");
  EXPECT_NE(errorOf(ini).find("[sweep]: run 1 (copy) repeats an earlier run's exact parameters"), std::string::npos)
      << errorOf(ini);
}
