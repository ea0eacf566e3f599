#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "gridtopo/core/error.h"
#include "gridtopo/mapping/map_run_ini.h"
#include "gridtopo/topology/topology_run_ini.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
fs::path tmpDir() { return fs::temp_directory_path() / ("gridtopo_map_run_ini_" + std::to_string(::getpid())); }
struct RemoveTmpDir : ::testing::Environment {
  void TearDown() override { fs::remove_all(tmpDir()); }
};
const auto* const kRemoveTmpDir = ::testing::AddGlobalTestEnvironment(new RemoveTmpDir);

fs::path tmp(const std::string& name, const std::string& text) {
  const fs::path d = tmpDir();
  fs::create_directories(d);
  std::ofstream(d / name) << text;
  return d / name;
}
const std::string kLog = std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.clf.gz";
const std::string kModel = std::string(GRIDTOPO_DATA_DIR) + "/models/places_model.yml";
}  // namespace

TEST(MapRunIni, ReadsEverySectionAndWritesItBackLoadable) {
  const auto path = tmp("run.ini", "[map_run]\ninput = " + kLog + "\noutput = out/x\nmodel = " + kModel +
                                       "\nmax_scans = 700\n[slam]\nparticles = 12\n[topology]\nthreads = 3\n"
                                       "[relaxation]\nmax_iterations = 7\n[correction]\nmin_room_area = 2.5\n"
                                       "[topology_builder]\nupdate_every = 50\n");
  const auto spec = mapping::loadMapRunIni(path.string());
  EXPECT_EQ(spec.input, kLog);
  EXPECT_EQ(spec.output, "out/x");
  EXPECT_EQ(spec.model, kModel);
  EXPECT_TRUE(spec.fromIni("input") && spec.fromIni("output") && spec.fromIni("model"));
  EXPECT_EQ(spec.max_scans, 700u);
  EXPECT_EQ(spec.slam.particles, 12);
  EXPECT_EQ(spec.topology.threads, 3);
  EXPECT_EQ(spec.topology.relaxation.max_iterations, 7);
  EXPECT_DOUBLE_EQ(spec.topology.correction.min_room_area, 2.5);
  EXPECT_EQ(spec.builder.update_every, 50u);
  mapping::checkMapRunSpec(spec);

  // The run's INI loads back to the same run, with absolute paths.
  const std::string text = mapping::mapRunIni(spec);
  const auto back = mapping::loadMapRunIni(tmp("back.ini", text).string());
  EXPECT_EQ(back.output, fs::absolute("out/x").lexically_normal().string());
  EXPECT_EQ(back.max_scans, 700u);
  EXPECT_EQ(back.slam.particles, 12);
  EXPECT_EQ(back.topology.relaxation.max_iterations, 7);
  EXPECT_EQ(back.builder.update_every, 50u);
  EXPECT_EQ(mapping::mapRunIni(back), text);
}

TEST(MapRunIni, MissingSectionsKeepTheDefaultsAndFlagsOverride) {
  const auto spec0 = mapping::loadMapRunIni(tmp("min.ini", "[map_run]\ninput = " + kLog + "\n").string());
  EXPECT_EQ(spec0.model, topology::kDefaultPlacesModel);
  EXPECT_FALSE(spec0.fromIni("model"));
  EXPECT_EQ(spec0.lines.of("model"), 1u);  // not in the file: the line of [map_run]
  EXPECT_EQ(spec0.lines.of("input"), 2u);
  EXPECT_EQ(spec0.slam.particles, slam::SlamOptions().particles);
  EXPECT_EQ(spec0.builder.update_every, 0u);
  try {
    mapping::checkMapRunSpec(spec0);
    FAIL() << "no output";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "[map_run] output");
    EXPECT_EQ(e.line(), 1u);  // the section, where the key belongs
  }
  auto spec = spec0;
  mapping::overrideRun(spec, {std::nullopt, std::string("o"), kModel, 10L});
  EXPECT_EQ(spec.output, "o");
  EXPECT_EQ(spec.model, kModel);
  EXPECT_EQ(spec.max_scans, 10u);
  EXPECT_EQ(spec.input, kLog);
  mapping::checkMapRunSpec(spec);
  EXPECT_THROW(mapping::overrideRun(spec, {std::nullopt, std::nullopt, std::nullopt, -1L}), InputError);
  mapping::overrideRun(spec, {std::string("no/such.clf"), std::nullopt, std::nullopt, std::nullopt});
  try {
    mapping::checkMapRunSpec(spec);
    FAIL() << "missing input accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "no/such.clf");  // a flag's file is named itself
  }
}

TEST(MapRunIni, UnknownSectionsAndKeysNameTheLine) {
  auto expectError = [](const std::string& text, std::size_t line, const std::string& field) {
    try {
      mapping::loadMapRunIni(tmp("bad.ini", text).string());
      FAIL() << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_EQ(e.field(), field) << e.what();
    }
  };
  expectError("[map_run]\n[slam_run]\ninput = x\n", 2, "[slam_run]");
  expectError("[map_run]\nevery = 3\n", 2, "[map_run] every");
  expectError("[map_run]\nmax_scans = lots\n", 2, "[map_run] max_scans");
  expectError("[slam]\nparticles = 3\nparticle = 4\n", 3, "[slam] particle");
  expectError("[topology_builder]\n\nupdate_every = 1.5\n", 3, "[topology_builder] update_every");
  expectError("[relaxation]\nmax_iterations = x\n", 2, "[relaxation] max_iterations");
}
