#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/run_app.h"
#include "gridtopo/io/trajectory_io.h"

namespace fs = std::filesystem;

namespace {
using Result = gridtopo::testing_app::AppRun;
Result run(const std::string& args) { return gridtopo::testing_app::runApp("gridtopo-slam", args); }
const std::string kIntel = std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.clf.gz";
}  // namespace

TEST(SlamApp, WritesEveryOutputForAShortIntelSlice) {
  const fs::path out = fs::temp_directory_path() / "gridtopo_slam_app_out";
  fs::remove_all(out);
  const Result r = run("-i " + kIntel + " -o " + out.string() + " -c " + GRIDTOPO_SOURCE_DIR +
                       "/config-ini/slam.ini -p 4 -t 2 -q --max-scans 400");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"map.png", "map_trajectory.png", "map.pgm", "map.yaml", "map.gridmap.gz", "map.simplemap",
                        "trajectory.txt", "stats.txt", "options.ini"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto traj = gridtopo::io::readTrajectory((out / "trajectory.txt").string());
  EXPECT_EQ(traj.size(), 400u);  // a pose for every scan
  std::ifstream stats(out / "stats.txt");
  std::string line;
  int lines = 0;
  while (std::getline(stats, line)) lines += !line.empty() && line[0] != '#';
  EXPECT_GT(lines, 20);
  EXPECT_LT(lines, 400);
}

TEST(SlamApp, BadIniValuesFailWithFileSectionAndKey) {
  const fs::path ini = fs::temp_directory_path() / "gridtopo_slam_app_bad.ini";
  const fs::path out = fs::temp_directory_path() / "gridtopo_slam_app_bad_out";
  fs::remove_all(out);
  std::ofstream(ini) << "[slam]\nparticles = 0\n";
  Result r = run("-i " + kIntel + " -o " + out.string() + " -c " + ini.string() + " -q --max-scans 10");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find(ini.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("[slam] particles"), std::string::npos) << r.output;
  std::ofstream(ini) << "[slam]\nresolution = -0.05\n";
  r = run("-i " + kIntel + " -o " + out.string() + " -c " + ini.string() + " -q --max-scans 10");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("[slam] resolution"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "trajectory.txt"));  // nothing written
  r = run("-i " + kIntel + " -o " + out.string() + " -p 0 -q --max-scans 10");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("particles"), std::string::npos) << r.output;
  r = run("-i /nonexistent.clf -o " + out.string() + " -q");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("/nonexistent.clf"), std::string::npos) << r.output;
}

// OUT/options.ini is a loadable [slam] section that reproduces the run: `gridtopo-slam -c OUT/options.ini` reads
// it back (command-line overrides included) and gives the same trajectory and the same options file.
TEST(SlamApp, OptionsIniOfARunReproducesIt) {
  const fs::path out = fs::temp_directory_path() / "gridtopo_slam_app_rerun_a";
  const fs::path again = fs::temp_directory_path() / "gridtopo_slam_app_rerun_b";
  fs::remove_all(out);
  fs::remove_all(again);
  Result r = run("-i " + kIntel + " -o " + out.string() + " -p 3 -s 11 -t 2 --proposal mode-only -q --max-scans 150");
  ASSERT_EQ(r.status, 0) << r.output;
  r = run("-i " + kIntel + " -o " + again.string() + " -c " + (out / "options.ini").string() + " -q --max-scans 150");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto slurp = [](const fs::path& p) {
    std::ostringstream s;
    s << std::ifstream(p).rdbuf();
    return s.str();
  };
  const std::string ini = slurp(out / "options.ini");
  EXPECT_EQ(ini.rfind("[slam]", 0), 0u) << ini;
  EXPECT_NE(ini.find("particles = 3"), std::string::npos) << ini;
  EXPECT_NE(ini.find("seed = 11"), std::string::npos) << ini;
  EXPECT_NE(ini.find("proposal = mode-only"), std::string::npos) << ini;
  EXPECT_EQ(slurp(again / "options.ini"), ini);
  // The identical trajectory (written with round-trip precision) and map.
  EXPECT_EQ(gridtopo::io::readTrajectory((out / "trajectory.txt").string()).size(), 150u);
  EXPECT_EQ(slurp(again / "trajectory.txt"), slurp(out / "trajectory.txt"));
  EXPECT_EQ(slurp(again / "map.pgm"), slurp(out / "map.pgm"));
  fs::remove_all(out);
  fs::remove_all(again);
}

// The reader's decisions against the log's word reach the user of gridtopo-slam, even with -q.
TEST(SlamApp, PrintsTheReadersWarnings) {
  const fs::path dir = fs::temp_directory_path() / "gridtopo_slam_app_warn";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream log(dir / "fov_radians.clf");
  log << "PARAM laser_front_laser_fov 3.14159 nohost 0\n";
  for (int i = 0; i < 5; ++i) {  // old FLASER lines: 181 readings, odometry x y theta twice, timestamps
    log << "FLASER 181";
    for (int k = 0; k < 181; ++k) log << " 3.0";
    log << " 0 0 0 0 0 0 " << 100 + i << " nohost " << 100 + i << "\n";
  }
  log.close();
  const Result r = run("-i " + (dir / "fov_radians.clf").string() + " -o " + (dir / "out").string() + " -p 2 -t 1 -q");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("gridtopo-slam: warning: " + (dir / "fov_radians.clf").string() +
                          ": PARAM laser_front_laser_fov 3.14159 read as radians (180 deg)"),
            std::string::npos)
      << r.output;
}
