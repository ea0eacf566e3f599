// The one writer of a SLAM run's output set (gridtopo-slam and the GUI): every file, or none.
#include <gtest/gtest.h>

#include "common/scratch.h"

#include <filesystem>
#include <fstream>

#include "gridtopo/io/map_io.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/options_ini.h"
#include "gridtopo/slam/rbpf_slam.h"
#include "gridtopo/slam/slam_outputs.h"

namespace fs = std::filesystem;
using namespace gridtopo;

namespace {
const char* kFiles[] = {"map.png",        "map_trajectory.png", "map.pgm",   "map.yaml",   "map.gridmap.gz",
                        "map.simplemap", "trajectory.txt",     "stats.txt", "options.ini"};

slam::SlamOutputs smallRun(std::vector<ScanRecord>& records) {
  sim::SimOptions so;
  so.seed = 3;
  auto log = sim::simulate(sim::FloorPlan::officeLoop(), {{2, 2, 0}, {8, 2, 0}}, so);
  records = log.records;
  slam::SlamOptions o;
  o.particles = 3;
  o.threads = 1;
  slam::RbpfSlam filter(o);
  for (const auto& r : records) filter.processScan(r);
  slam::SlamOutputs out;
  out.grid = slam::toOccupancyGrid(filter.bestParticle().map);
  out.trajectory = filter.trajectory();
  out.trajectory_header = {"test"};
  out.simplemap = slam::simpleMapOf(filter.bestParticle().node, records);
  out.stats = "# stats\n";
  out.options_ini = slam::slamOptionsIni(o);
  EXPECT_EQ(out.simplemap.size(), filter.stepsProcessed());  // one frame per processed scan
  return out;
}
}  // namespace

TEST(SlamOutputs, WritesTheWholeSet) {
  std::vector<ScanRecord> records;
  const slam::SlamOutputs o = smallRun(records);
  const fs::path dir = gridtopo::test::scratchPath("slam_outputs_test");
  fs::remove_all(dir);
  slam::writeSlamOutputs(dir.string(), o);
  for (const char* f : kFiles) EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_EQ(io::readTrajectory((dir / "trajectory.txt").string()).size(), records.size());
  const auto back = io::readGridMap((dir / "map.yaml").string());
  EXPECT_EQ(back->getSizeX(), o.grid.getSizeX());
  EXPECT_EQ(back->getSizeY(), o.grid.getSizeY());
  std::ifstream ini(dir / "options.ini");
  std::string text((std::istreambuf_iterator<char>(ini)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, o.options_ini);
}

TEST(SlamOutputs, WritesNothingWhenOneFileFails) {
  std::vector<ScanRecord> records;
  const slam::SlamOutputs o = smallRun(records);
  const fs::path dir = gridtopo::test::scratchPath("slam_outputs_fail");
  fs::remove_all(dir);
  fs::create_directories(dir / "map.simplemap");  // a directory where a file must go: that write fails
  EXPECT_ANY_THROW(slam::writeSlamOutputs(dir.string(), o));
  for (const char* f : kFiles) {
    if (std::string(f) == "map.simplemap") continue;  // the directory put there
    EXPECT_FALSE(fs::exists(dir / f)) << f;
  }
}
