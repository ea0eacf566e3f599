// The scans gridtopo-import converts (sim/import_source.h): a log file, or the simulated pillar room with its
// ground truth staged in the caller's output set.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "common/scratch.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/sim/import_source.h"
#include "gridtopo/sim/simulator.h"

using namespace gridtopo;
namespace fs = std::filesystem;

TEST(ImportSource, TheSimulatedLogAndItsGroundTruth) {
  const fs::path dir = test::scratch("sim");
  const std::string gt = (dir / "gt.txt").string();
  OutputSet outputs;
  const sim::ImportSource s = sim::readImportSource(std::nullopt, 60, 3, gt, {}, outputs);
  EXPECT_EQ(s.name, "simulated (60 scans, seed 3)");
  EXPECT_EQ(s.info.format, io::LogFormat::Simulated);
  ASSERT_EQ(s.scans.size(), 60u);
  // The same log as the simulator's with that seed, scan for scan.
  auto options = sim::pillarRoomOptions();
  options.seed = 3;
  const auto log = sim::simulatePillarRoom(60, options);
  EXPECT_EQ(s.scans.back().scan.ranges, log.records.back().scan.ranges);
  EXPECT_FALSE(fs::exists(gt));  // staged, not yet written
  outputs.commit();
  const auto truth = io::readTrajectory(gt);
  ASSERT_EQ(truth.size(), 60u);
  EXPECT_NEAR(truth[7].pose.x, log.timedTruth()[7].pose.x, 1e-6);
}

TEST(ImportSource, ALogFileIsRead) {
  OutputSet outputs;
  const std::string clf = std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.clf.gz";
  const sim::ImportSource s = sim::readImportSource(clf, std::nullopt, 42, std::nullopt, {}, outputs);
  EXPECT_EQ(s.name, clf);
  EXPECT_EQ(s.info.format, io::LogFormat::Carmen);
  EXPECT_EQ(s.scans.size(), 13631u);
}

TEST(ImportSource, ExactlyOneSourceAndGroundTruthOnlyWhenSimulated) {
  OutputSet outputs;
  EXPECT_THROW(sim::readImportSource(std::nullopt, std::nullopt, 1, std::nullopt, {}, outputs), std::invalid_argument);
  EXPECT_THROW(sim::readImportSource(std::string("a.clf"), 10, 1, std::nullopt, {}, outputs), std::invalid_argument);
  EXPECT_THROW(sim::readImportSource(std::string("a.clf"), std::nullopt, 1, std::string("gt.txt"), {}, outputs),
               std::invalid_argument);
}
