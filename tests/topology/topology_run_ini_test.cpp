#include <gtest/gtest.h>

#include "common/scratch.h"

#include <filesystem>
#include <fstream>

#include "gridtopo/core/error.h"
#include "gridtopo/topology/topology_run_ini.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
const std::string kSource = GRIDTOPO_SOURCE_DIR;
}

TEST(TopologyRunIni, TheShippedRunIniLoads) {
  const topology::TopologyRunSpec s = topology::loadTopologyRunIni(kSource + "/config-ini/run-topology.ini");
  EXPECT_EQ(s.map, "datasets/places/maps/lab_intel.png");
  EXPECT_EQ(s.model, "datasets/models/places_model.yml");
  EXPECT_EQ(s.output, "out/lab_intel");
  EXPECT_TRUE(s.fromIni("map"));
  EXPECT_EQ(s.options.threads, 2);
  EXPECT_EQ(s.options.relaxation.max_iterations, 30);
  EXPECT_EQ(s.options.correction.min_room_area, 4.0);
}

// config-ini/topology.ini documents every key: read as a RUN.ini, none of its keys is unknown to the saved table.
TEST(TopologyRunIni, EveryKeyOfTheDocumentedIniIsKnown) {
  const topology::TopologyRunSpec s = topology::loadTopologyRunIni(kSource + "/config-ini/topology.ini");
  EXPECT_TRUE(s.map.empty());
  EXPECT_EQ(s.model, topology::kDefaultPlacesModel);
}

TEST(TopologyRunIni, TheRunsIniLoadsBackToTheSameRun) {
  const fs::path dir = test::scratch("run_ini");
  topology::TopologyRunSpec spec;
  spec.map = "/maps/a.png";
  spec.output = "/tmp/out";
  spec.options.correction.min_room_area = 1.0 / 3.0;
  spec.options.relaxation.tolerance = 2e-4;
  spec.options.segmentation = "doorways";
  spec.options.blob_vote.enabled = true;
  spec.options.grid_free_threshold = 210;
  const std::string text = topology::topologyRunIni(spec);
  EXPECT_EQ(text.rfind("[topology_run]\nmap = /maps/a.png\nmodel = " +
                           (fs::current_path() / topology::kDefaultPlacesModel).string() +
                           "\noutput = /tmp/out\ntrajectory = \n\n[topology]\n",
                       0),
            0u)
      << text;
  std::ofstream(dir / "run.ini") << text;
  const topology::TopologyRunSpec back = topology::loadTopologyRunIni((dir / "run.ini").string());
  EXPECT_EQ(back.options.correction.min_room_area, 1.0 / 3.0);
  EXPECT_EQ(back.options.relaxation.tolerance, 2e-4);
  EXPECT_EQ(back.options.segmentation, "doorways");
  EXPECT_TRUE(back.options.blob_vote.enabled);
  EXPECT_EQ(back.options.grid_free_threshold, 210);
  EXPECT_EQ(topology::topologyRunIni(back), text);
  fs::remove_all(dir);
}

TEST(TopologyRunIni, AMissingMapOrOutputIsNamed) {
  topology::TopologyRunSpec spec;
  try {
    topology::checkTopologyRunSpec(spec);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "[topology_run] map");
  }
  spec.map = "/maps/a.png";
  try {
    topology::checkTopologyRunSpec(spec);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "[topology_run] output");
  }
}

TEST(TopologyRunIni, FlagsOverrideSingleValuesAndAreChecked) {
  topology::TopologyRunSpec spec;
  spec.model = "a.yml";
  spec.lines.keys["model"] = 3;
  topology::overrideRun(spec, {std::string("b.yml"), std::string("/out"), std::string("t.txt"), 0.1, 3});
  EXPECT_EQ(spec.model, "b.yml");
  EXPECT_EQ(spec.trajectory, "t.txt");
  EXPECT_FALSE(spec.fromIni("model"));
  EXPECT_EQ(spec.output, "/out");
  EXPECT_EQ(spec.options.resolution, 0.1);
  EXPECT_EQ(spec.options.threads, 3);
  topology::overrideRun(spec, {});
  EXPECT_EQ(spec.options.threads, 3);  // unset flags keep the values
  EXPECT_THROW(topology::overrideRun(spec, {std::nullopt, std::nullopt, std::nullopt, -1.0, std::nullopt}), InputError);
  EXPECT_THROW(topology::overrideRun(spec, {std::nullopt, std::nullopt, std::nullopt, std::nullopt, 0}), InputError);
}

// Without -m the apps use the shipped model from any working directory: $GRIDTOPO_DATA_DIR first, then beside the
// executable, then the source tree's datasets/ (gridtopo::findDataFile). A model named otherwise is kept as given.
TEST(TopologyRunIni, TheDefaultModelIsFoundFromAnyWorkingDirectory) {
  const fs::path elsewhere = test::scratch("elsewhere");
  const fs::path old = fs::current_path();
  fs::current_path(elsewhere);
  topology::TopologyRunFlags flags;
  flags.output = "out";
  const auto spec = topology::topologyRunOfCommandLine(kSource + "/datasets/places/maps/lab_intel.png", {}, flags);
  EXPECT_TRUE(fs::equivalent(spec.model, kSource + "/datasets/models/places_model.yml")) << spec.model;
  // $GRIDTOPO_DATA_DIR comes first.
  fs::create_directories("data/models");
  fs::copy_file(kSource + "/datasets/models/places_model.yml", "data/models/places_model.yml");
  ::setenv("GRIDTOPO_DATA_DIR", (elsewhere / "data").c_str(), 1);
  const auto from_env = topology::topologyRunOfCommandLine(kSource + "/datasets/places/maps/lab_intel.png", {}, flags);
  ::unsetenv("GRIDTOPO_DATA_DIR");
  EXPECT_EQ(from_env.model, (elsewhere / "data/models/places_model.yml").string());
  // Another name is the user's: left to the reader, which names it when it is missing.
  flags.model = "mine.yml";
  EXPECT_EQ(topology::topologyRunOfCommandLine(kSource + "/datasets/places/maps/lab_intel.png", {}, flags).model,
            "mine.yml");
  fs::current_path(old);
}
