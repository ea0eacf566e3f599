// gridtopo-simulate-maps end to end: the stored derived maps are remade byte for byte; bad input exits 1 naming the
// culprit and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/run_app.h"
#include "common/scratch.h"

namespace fs = std::filesystem;
using gridtopo::testing_app::runApp;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}
const std::string kData = GRIDTOPO_DATA_DIR;
const std::string kSlamIni = std::string(GRIDTOPO_SOURCE_DIR) + "/config-ini/slam.ini";
}  // namespace

TEST(SimulateMapsApp, RemakesTheStoredMapByteForByte) {
  const auto out = gridtopo::test::scratch("derived");
  const auto r = runApp("gridtopo-simulate-maps", "-d " + kData + "/places -o " + out.string() + " -c " + kSlamIni +
                                                      " -s 1 --maps lab_ipa,Fr52");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* name : {"lab_ipa", "Fr52"}) {
    const auto made = slurp(out / (std::string(name) + "_sim_map.png"));
    ASSERT_FALSE(made.empty()) << name;
    EXPECT_EQ(made, slurp(fs::path(kData) / "places/derived" / (std::string(name) + "_sim_map.png"))) << name;
  }
  EXPECT_NE(slurp(out / "manifest.txt").find("lab_ipa 688 "), std::string::npos) << slurp(out / "manifest.txt");
}

TEST(SimulateMapsApp, RemakesTheStoredSlamVariantByteForByte) {
  // The SLAM variant of the smallest plan (688 scans, 338 processed by the 30-particle default SLAM; about 10 s):
  // the same map as datasets/places/derived/slam (made with -t 1; the SLAM gives the same map for any thread count), and its drift in the manifest.
  const auto out = gridtopo::test::scratch("derived_slam");
  const auto r = runApp("gridtopo-simulate-maps", "--variant slam -t 1 -d " + kData + "/places -o " + out.string() +
                                                      " -c " + kSlamIni + " -s 1 --maps lab_ipa");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto made = slurp(out / "lab_ipa_sim_map.png");
  ASSERT_FALSE(made.empty());
  EXPECT_EQ(made, slurp(fs::path(kData) / "places/derived/slam/lab_ipa_sim_map.png"));
  EXPECT_NE(made, slurp(fs::path(kData) / "places/derived/lab_ipa_sim_map.png"));  // not the exact variant's map
  // name scans path rooms entered unreachable goals known free | processed final_error heading max_error ...
  EXPECT_NE(slurp(out / "manifest.txt").find("lab_ipa 688 64.4 6 5 0 14 0.7622 0.6883 338 0.013 "), std::string::npos)
      << slurp(out / "manifest.txt");
}

TEST(SimulateMapsApp, BadInputExitsOneAndWritesNothing) {
  const auto out = gridtopo::test::scratch("bad");
  auto r = runApp("gridtopo-simulate-maps", "-d " + kData + "/places -o " + (out / "x").string() + " -c " + kSlamIni +
                                                " --maps nowhere");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("nowhere"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "x"));
  r = runApp("gridtopo-simulate-maps", "-d " + kData + "/places -o " + (out / "x").string() + " -c " +
                                           (out / "missing.ini").string() + " --maps lab_ipa");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("missing.ini"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "x"));
  // The -c INI is read as strictly as gridtopo-slam's: a typo is refused with file, line and a "did you mean".
  const std::string typo = (out / "typo.ini").string();
  std::ofstream(typo) << "[slam]\nparticles = 30\nmax_usable_rangee = 20\n";
  r = runApp("gridtopo-simulate-maps", "-d " + kData + "/places -o " + (out / "x").string() + " -c " + typo +
                                           " --maps lab_ipa");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(r.output.rfind("gridtopo-simulate-maps: error: " + typo + ":3: [slam] max_usable_rangee: unknown key (did "
                           "you mean 'max_usable_range'?",
                           0),
            0u)
      << r.output;
  EXPECT_FALSE(fs::exists(out / "x"));
  r = runApp("gridtopo-simulate-maps", "--variant drifted -d " + kData + "/places -o " + (out / "x").string() +
                                           " -c " + kSlamIni + " --maps lab_ipa");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("--variant"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "x"));
}
