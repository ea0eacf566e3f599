#include <gtest/gtest.h>

#include "common/scratch.h"

#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/slam/slam_options.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
std::string loadError(const std::string& body) {
  const fs::path p = gridtopo::test::scratchPath("slam_bad.ini");
  std::ofstream(p) << "[slam]\n" << body << "\n";
  mrpt::config::CConfigFile ini(p.string());
  slam::SlamOptions o;
  try {
    o.loadFromConfigFile(ini, "slam");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), p.string());
    return e.what();
  }
  return "";
}
}  // namespace

TEST(SlamOptions, BadValuesNameFileSectionAndKey) {
  const std::string path = (gridtopo::test::scratchPath("slam_bad.ini")).string();
  std::string e = loadError("particles = 0");
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("[slam] particles"), std::string::npos) << e;
  e = loadError("resolution = -0.05");
  EXPECT_NE(e.find("[slam] resolution"), std::string::npos) << e;
  EXPECT_NE(e.find("must be in (0, 10], got -0.05"), std::string::npos) << e;
  EXPECT_NE(loadError("particles = ten").find("[slam] particles"), std::string::npos);
  EXPECT_NE(loadError("particles = 2.5").find("integer"), std::string::npos);
  EXPECT_NE(loadError("resolution = nan").find("[slam] resolution"), std::string::npos);
  EXPECT_NE(loadError("likelihood_gain = 0").find("likelihood_gain"), std::string::npos);
  EXPECT_NE(loadError("resample_threshold = 1.5").find("resample_threshold"), std::string::npos);
  EXPECT_NE(loadError("proposal = optimal").find("[slam] proposal"), std::string::npos);
  EXPECT_NE(loadError("clear_no_return = maybe").find("clear_no_return"), std::string::npos);
  EXPECT_NE(loadError("seed = -3").find("[slam] seed"), std::string::npos);
  EXPECT_NE(loadError("match_kernel = 9").find("match_kernel"), std::string::npos);
  EXPECT_NE(loadError("motion_scale_sigma = -0.01").find("[slam] motion_scale_sigma"), std::string::npos);
  EXPECT_NE(loadError("motion_scale_walk_sigma = 0.5").find("[slam] motion_scale_walk_sigma"), std::string::npos);
  EXPECT_EQ(loadError("particles = 7\nresolution = 0.1"), "");
}

TEST(SlamOptions, LoadsDumpsAndRoundTrips) {
  mrpt::config::CConfigFileMemory ini;
  ini.write("s", "particles", "8");
  ini.write("s", "proposal", "odometry");
  ini.write("s", "resolution", "0.1");
  ini.write("s", "clear_no_return", "false");
  ini.write("s", "seed", "123456789012");
  slam::SlamOptions o;
  o.loadFromConfigFile(ini, "s");
  EXPECT_EQ(o.particles, 8);
  EXPECT_EQ(o.proposal.type, slam::ProposalType::Odometry);
  EXPECT_DOUBLE_EQ(o.resolution, 0.1);
  EXPECT_FALSE(o.beams.clear_no_return);
  EXPECT_EQ(o.seed, 123456789012ULL);
  std::ostringstream dump;
  o.dumpToTextStream(dump);
  // One line per key, its value after the '=' that the column of the longest key's name aligns.
  EXPECT_TRUE(std::regex_search(dump.str(), std::regex("\nparticles += 8\n"))) << dump.str();
  EXPECT_TRUE(std::regex_search(dump.str(), std::regex("\nproposal += odometry\n"))) << dump.str();
  mrpt::config::CConfigFileMemory saved;
  o.saveToConfigFile(saved, "x");
  slam::SlamOptions back;
  back.loadFromConfigFile(saved, "x");
  std::ostringstream dump2;
  back.dumpToTextStream(dump2);
  EXPECT_EQ(dump.str(), dump2.str());
}

TEST(SlamOptions, ShippedIniFilesLoad) {
  for (const char* name : {"slam.ini"}) {  // one default INI for every log (issue 13)
    const std::string p = std::string(GRIDTOPO_SOURCE_DIR) + "/config-ini/" + name;
    if (!fs::exists(p)) continue;
    mrpt::config::CConfigFile ini(p);
    slam::SlamOptions o;
    EXPECT_NO_THROW(o.loadFromConfigFile(ini, "slam")) << p;
  }
  ASSERT_TRUE(fs::exists(std::string(GRIDTOPO_SOURCE_DIR) + "/config-ini/slam.ini"));
}

TEST(SlamOptions, DefaultIniDocumentsEveryKeyWithTheCodeDefaults) {
  mrpt::config::CConfigFile ini(std::string(GRIDTOPO_SOURCE_DIR) + "/config-ini/slam.ini");
  slam::SlamOptions from_ini;
  from_ini.loadFromConfigFile(ini, "slam");
  std::ostringstream a, b;
  from_ini.dumpToTextStream(a);
  slam::SlamOptions().dumpToTextStream(b);
  EXPECT_EQ(a.str(), b.str());
  // Every key the options know is written in the file.
  mrpt::config::CConfigFileMemory saved;
  slam::SlamOptions().saveToConfigFile(saved, "slam");
  std::vector<std::string> keys;
  saved.getAllKeys("slam", keys);
  for (const auto& k : keys) EXPECT_TRUE(ini.keyExists("slam", k)) << k << " is not documented in slam.ini";
  for (const auto& k : slam::loopClosureOptionSchema().keys())
    EXPECT_TRUE(ini.keyExists("loop_closure", k)) << k << " is not documented in slam.ini's [loop_closure]";
}

TEST(SlamOptions, LoopClosureKeysLoadFromTheirOwnSectionAndBadValuesNameIt) {
  mrpt::config::CConfigFileMemory ini;
  ini.write("slam", "particles", "7");
  ini.write("loop_closure", "enabled", "false");
  ini.write("loop_closure", "window_xy_max", "5");
  slam::SlamOptions o;
  o.loadFromConfigFile(ini, "slam");
  EXPECT_EQ(o.particles, 7);
  EXPECT_FALSE(o.loop_closure.enabled);
  EXPECT_DOUBLE_EQ(o.loop_closure.window_xy_max, 5.0);
  // Saved back beside [slam], and loaded again to the same options.
  mrpt::config::CConfigFileMemory saved;
  o.saveToConfigFile(saved, "slam");
  slam::SlamOptions again;
  again.loadFromConfigFile(saved, "slam");
  EXPECT_FALSE(again.loop_closure.enabled);
  EXPECT_DOUBLE_EQ(again.loop_closure.window_xy_max, 5.0);
  mrpt::config::CConfigFileMemory bad;
  bad.write("loop_closure", "min_score", "1.5");
  try {
    slam::SlamOptions b;
    b.loadFromConfigFile(bad, "slam");
    FAIL() << "min_score 1.5 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("[loop_closure] min_score"), std::string::npos) << e.what();
  }
}
