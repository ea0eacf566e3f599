#include <gtest/gtest.h>

#include "common/scratch.h"

#include <filesystem>
#include <fstream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"
#include "gridtopo/slam/slam_run_ini.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
const std::string kSource = GRIDTOPO_SOURCE_DIR;
std::string fieldOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.field();
  }
  return "no error";
}
}  // namespace

TEST(SlamRunIni, TheShippedRunIniLoads) {
  const slam::SlamRunSpec s = slam::loadSlamRunIni(kSource + "/config-ini/run-slam.ini");
  EXPECT_EQ(s.input, "datasets/slam/intel.clf.gz");
  EXPECT_EQ(s.output, "out/intel");
  EXPECT_EQ(s.max_scans, 0u);
  EXPECT_TRUE(s.fromIni("input"));
  EXPECT_TRUE(s.fromIni("output"));
  // The lines of the run section and its keys, for the checks after loading.
  const IniFile layout = IniFile::read(kSource + "/config-ini/run-slam.ini");
  EXPECT_EQ(s.lines.section, layout.line("slam_run"));
  EXPECT_EQ(s.lines.of("input"), layout.line("slam_run", "input"));
  EXPECT_GT(s.lines.of("output"), s.lines.of("input"));
  EXPECT_EQ(s.options.particles, 30);
  EXPECT_EQ(s.options.threads, 2);
}

// config-ini/slam.ini documents every key: read as a RUN.ini, none of its keys is unknown.
TEST(SlamRunIni, EveryKeyOfTheDocumentedIniIsKnown) {
  const slam::SlamRunSpec s = slam::loadSlamRunIni(kSource + "/config-ini/slam.ini");
  EXPECT_TRUE(s.input.empty());
  EXPECT_FALSE(s.fromIni("input"));
  EXPECT_EQ(s.lines.of("input"), 0u);
}

TEST(SlamRunIni, TheRunsIniLoadsBackToTheSameRun) {
  const fs::path dir = test::scratch("run_ini");
  slam::SlamRunSpec spec;
  spec.input = "some/log.clf";
  spec.output = "/tmp/x/../out";
  spec.max_scans = 77;
  spec.options.particles = 5;
  spec.options.resolution = 1.0 / 30.0;  // not kept by six digits
  spec.options.proposal.type = slam::ProposalType::ModeOnly;
  const std::string text = slam::slamRunIni(spec);
  EXPECT_EQ(text.rfind("[slam_run]\ninput = " + (fs::current_path() / "some/log.clf").string() +
                           "\noutput = /tmp/out\nmax_scans = 77\n\n[slam]\n",
                       0),
            0u)
      << text;
  std::ofstream(dir / "run.ini") << text;
  const slam::SlamRunSpec back = slam::loadSlamRunIni((dir / "run.ini").string());
  EXPECT_EQ(back.max_scans, 77u);
  EXPECT_EQ(back.options.resolution, 1.0 / 30.0);
  EXPECT_EQ(back.options.proposal.type, slam::ProposalType::ModeOnly);
  EXPECT_EQ(slam::slamRunIni(back), text);
  fs::remove_all(dir);
}

TEST(SlamRunIni, FlagsAreCheckedAndNamed) {
  slam::SlamOptions o;
  slam::overrideOptions(o, {3, 9, 1, std::string("odometry")});
  EXPECT_EQ(o.particles, 3);
  EXPECT_EQ(o.seed, 9u);
  EXPECT_EQ(o.threads, 1);
  EXPECT_EQ(o.proposal.type, slam::ProposalType::Odometry);
  slam::overrideOptions(o, {});
  EXPECT_EQ(o.particles, 3);  // unset flags keep the values
  EXPECT_EQ(fieldOf([&] { slam::overrideOptions(o, {std::nullopt, -1, std::nullopt, std::nullopt}); }), "--seed");
  EXPECT_EQ(fieldOf([&] { slam::overrideOptions(o, {std::nullopt, std::nullopt, std::nullopt, std::string("x")}); }),
            "--proposal");
  EXPECT_EQ(fieldOf([&] { slam::overrideOptions(o, {0, std::nullopt, std::nullopt, std::nullopt}); }), "[slam] particles");
}

TEST(SlamRunIni, AMissingInputOrOutputIsNamed) {
  slam::SlamRunSpec spec;
  EXPECT_EQ(fieldOf([&] { slam::checkSlamRunSpec(spec); }), "[slam_run] input");
  spec.input = kSource + "/datasets/slam/intel.clf.gz";
  EXPECT_EQ(fieldOf([&] { slam::checkSlamRunSpec(spec); }), "[slam_run] output");
  spec.output = "/tmp/x";
  EXPECT_NO_THROW(slam::checkSlamRunSpec(spec));
  spec.input = "/nonexistent.clf";  // given by -i: the error names the file itself
  try {
    slam::checkSlamRunSpec(spec);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent.clf");
  }
}
