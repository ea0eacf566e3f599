// gridtopo-simulate-maps' arguments to a run (simtrain::simulateMapsRunOf): defaults per variant, the manifest's
// command line, and bad values named by their flag.
#include <gtest/gtest.h>

#include <string>

#include "gridtopo/core/error.h"
#include "gridtopo/simtrain/simulate_plans.h"

using namespace gridtopo;
using namespace gridtopo::simtrain;

namespace {
SimulateMapsArgs noIni() {
  SimulateMapsArgs a;
  a.slam_ini = "";  // built-in [slam] defaults: the test does not depend on the working directory
  return a;
}

std::string flagOf(const SimulateMapsArgs& a) {
  try {
    simulateMapsRunOf(a);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(SimulateMapsRun, EachVariantWritesToItsOwnDirectoryByDefault) {
  SimulateMapsArgs a = noIni();
  const SimulateMapsRun exact = simulateMapsRunOf(a);
  EXPECT_EQ(exact.output, "datasets/places/derived");
  EXPECT_EQ(exact.options.variant, MapVariant::Exact);
  EXPECT_TRUE(exact.only.empty());
  a.variant = "slam";
  const SimulateMapsRun slam = simulateMapsRunOf(a);
  EXPECT_EQ(slam.output, "datasets/places/derived/slam");
  EXPECT_EQ(slam.options.variant, MapVariant::Slam);
  a.output = "/tmp/x";
  EXPECT_EQ(simulateMapsRunOf(a).output, "/tmp/x");
}

TEST(SimulateMapsRun, OptionsAndTheCommandThatRemakesTheMaps) {
  SimulateMapsArgs a = noIni();
  a.variant = "slam";
  a.seed = 7;
  a.threads = 1;
  a.room_visit_probability = 0.5;
  a.clearance = 0.3;
  a.maps = "lab_ipa,,Fr52";
  a.no_return_probability = 0.03;
  const SimulateMapsRun r = simulateMapsRunOf(a);
  EXPECT_EQ(r.options.laser.seed, 7u);
  EXPECT_EQ(r.options.tour.seed, 7u);
  EXPECT_EQ(r.options.slam.threads, 1);
  EXPECT_DOUBLE_EQ(r.options.tour.room_visit_probability, 0.5);
  EXPECT_DOUBLE_EQ(r.options.tour.clearance, 0.3);
  EXPECT_DOUBLE_EQ(r.options.laser.dropout_probability, 0.03);
  ASSERT_EQ(r.only.size(), 2u);
  EXPECT_EQ(r.only[0], "lab_ipa");
  EXPECT_EQ(r.only[1], "Fr52");
  EXPECT_EQ(r.command,
            "gridtopo-simulate-maps --variant slam -d datasets/places -o datasets/places/derived/slam -c '' -s 7 "
            "--room-visit-probability 0.5 --clearance 0.3 --maps lab_ipa,,Fr52 --no-return-probability 0.03");
  // The default rate is the laser's own (TrainingMapOptions::defaultLaser) and is left out of the command.
  EXPECT_DOUBLE_EQ(simulateMapsRunOf(noIni()).options.laser.dropout_probability,
                   TrainingMapOptions::defaultLaser().dropout_probability);
  EXPECT_EQ(simulateMapsRunOf(noIni()).command.find("--no-return-probability"), std::string::npos);
}

TEST(SimulateMapsRun, BadValuesNameTheirFlag) {
  SimulateMapsArgs a = noIni();
  a.variant = "exactly";
  EXPECT_NE(flagOf(a).find("--variant"), std::string::npos);
  a = noIni();
  a.seed = -1;
  EXPECT_NE(flagOf(a).find("--seed"), std::string::npos);
  a = noIni();
  a.room_visit_probability = 1.5;
  EXPECT_NE(flagOf(a).find("--room-visit-probability"), std::string::npos);
  a = noIni();
  a.clearance = -0.1;
  EXPECT_NE(flagOf(a).find("--clearance"), std::string::npos);
  a = noIni();
  a.no_return_probability = 1.0;
  EXPECT_NE(flagOf(a).find("--no-return-probability"), std::string::npos);
  a = noIni();
  a.slam_ini = "/nonexistent/slam.ini";
  EXPECT_NE(flagOf(a).find("/nonexistent/slam.ini"), std::string::npos);
}
