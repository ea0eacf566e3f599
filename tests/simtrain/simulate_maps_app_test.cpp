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
}
