// gridtopo-simulate-maps end to end: the stored derived maps are remade byte for byte; bad input exits 1 naming the
// culprit and writes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

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
    const auto poses = slurp(out / (std::string(name) + "_sim_trajectory.txt"));
    EXPECT_TRUE(poses == slurp(fs::path(kData) / "places/derived" / (std::string(name) + "_sim_trajectory.txt")))
        << name;
  }
  // The trajectory is in the plan's frame (lower-left corner at 0 0, 0.05 m cells): every pose of lab_ipa's run lies
  // on a free cell of the plan, one pose per scan.
  const cv::Mat plan = cv::imread(kData + "/places/maps/lab_ipa_original.png", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(plan.empty());
  std::istringstream lines(slurp(out / "lab_ipa_sim_trajectory.txt"));
  int poses = 0, off_free = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    double t = 0, x = 0, y = 0, theta = 0;
    ASSERT_TRUE(static_cast<bool>(std::istringstream(line) >> t >> x >> y >> theta)) << line;
    const int col = static_cast<int>(std::floor(x / 0.05));
    const int row = plan.rows - 1 - static_cast<int>(std::floor(y / 0.05));
    ++poses;
    const bool inside = row >= 0 && row < plan.rows && col >= 0 && col < plan.cols;
    off_free += !(inside && plan.at<unsigned char>(row, col) >= 250);
  }
  EXPECT_EQ(poses, 688);
  EXPECT_EQ(off_free, 0);
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
  // The SLAM's poses, not the true ones.
  const auto poses = slurp(out / "lab_ipa_sim_trajectory.txt");
  EXPECT_TRUE(poses == slurp(fs::path(kData) / "places/derived/slam/lab_ipa_sim_trajectory.txt"));
  EXPECT_FALSE(poses == slurp(fs::path(kData) / "places/derived/lab_ipa_sim_trajectory.txt"));
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
