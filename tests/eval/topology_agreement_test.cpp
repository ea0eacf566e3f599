// Two topologies of one building compared (topology_agreement.h, gridtopo-topology-compare --reference-topology):
// lab_intel's labelled plan as one topology, the same plan shifted in its image with one room's places taken away
// and one room relabelled as the other.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>

#include "common/run_app.h"
#include "common/scratch.h"
#include "gridtopo/eval/topology_agreement.h"
#include "gridtopo/places/place_label.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
const std::string kPlaces = std::string(GRIDTOPO_DATA_DIR) + "/places";

cv::Mat shifted(const cv::Mat& m, int dx, int dy, cv::Scalar fill) {
  cv::Mat out;
  cv::warpAffine(m, out, cv::Mat(cv::Matx23d(1, 0, dx, 0, 1, dy)), m.size(), cv::INTER_NEAREST, cv::BORDER_CONSTANT,
                 fill);
  return out;
}
}  // namespace

TEST(TopologyAgreement, CountsCommonPlacesTheirLabelsAndWhatEachLacks) {
  const fs::path d = test::scratch("topology_agreement");
  const cv::Mat map = cv::imread(kPlaces + "/maps/lab_intel.png", cv::IMREAD_GRAYSCALE);
  const cv::Mat codes = cv::imread(kPlaces + "/labelled/training_intel.png", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(map.empty());
  ASSERT_EQ(codes.size(), map.size());
  // The plan's labels on its free cells only (what a topology's labels.png holds).
  cv::Mat a_codes = codes.clone();
  a_codes.setTo(0, map <= 250);
  // The reference: shifted by (12, -7) cells; a 40 x 40 block of places removed at (100, 100) of the first's frame,
  // a 30 x 30 block of room turned into corridor.
  const int dx = 12, dy = -7;
  cv::Mat b_map = shifted(map, dx, dy, cv::Scalar(128));
  cv::Mat b_codes = shifted(a_codes, dx, dy, cv::Scalar(0));
  const cv::Rect gone(100 + dx, 100 + dy, 40, 40);
  const long long gone_places = cv::countNonZero(a_codes(cv::Rect(100, 100, 40, 40)) > 0);
  b_codes(gone).setTo(0);
  // A block of room cells relabelled corridor.
  cv::Rect relabel;
  long long relabelled = 0;
  for (int y = 0; y + 30 < a_codes.rows && !relabelled; y += 10)
    for (int x = 200; x + 30 < a_codes.cols && !relabelled; x += 10) {
      const cv::Rect r(x, y, 30, 30);
      if (cv::countNonZero(a_codes(r) == 77) == 900) {
        relabel = r;
        relabelled = 900;
      }
    }
  ASSERT_EQ(relabelled, 900);
  b_codes(relabel + cv::Point(dx, dy)).setTo(115);
  fs::create_directories(d / "a");
  fs::create_directories(d / "b");
  ASSERT_TRUE(cv::imwrite((d / "a.png").string(), map));
  ASSERT_TRUE(cv::imwrite((d / "a/labels.png").string(), a_codes));
  ASSERT_TRUE(cv::imwrite((d / "b.png").string(), b_map));
  ASSERT_TRUE(cv::imwrite((d / "b/labels.png").string(), b_codes));

  const eval::TopologyAgreement r = eval::compareTopologies({(d / "a.png").string(), (d / "a").string()},
                                                            {(d / "b.png").string(), (d / "b").string()},
                                                            topology::TopologyOptions());
  EXPECT_GT(r.alignment.correlation, 0.95);
  EXPECT_NEAR(r.alignment.map_to_reference(0, 2), dx, 0.5);
  EXPECT_NEAR(r.alignment.map_to_reference(1, 2), dy, 0.5);
  const long long places_a = cv::countNonZero(a_codes > 0);
  // Every place of the first is common but the removed block's (a cell or two of the alignment's rounding aside).
  EXPECT_NEAR(static_cast<double>(r.only_here), static_cast<double>(gone_places), 20.0);
  EXPECT_NEAR(static_cast<double>(r.both), static_cast<double>(places_a - gone_places), 20.0);
  EXPECT_NEAR(static_cast<double>(r.both - r.agree), 900.0, 20.0);
  EXPECT_NEAR(static_cast<double>(r.confusion[0][1]), 900.0, 20.0);
  EXPECT_LT(r.only_reference, 40);
  EXPECT_NEAR(r.onlyHereM2(), static_cast<double>(gone_places) * 0.05 * 0.05, 0.1);

  // The app's mode prints the same figures and writes the overlay; a plan and a topology together are refused.
  const auto run = testing_app::runApp(
      "gridtopo-topology-compare", (d / "a.png").string() + " " + (d / "a").string() + " --reference-topology " +
                                       (d / "b.png").string() + " --reference-topology " + (d / "b").string() +
                                       " --overlay " + (d / "agree.png").string());
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("labels agree on"), std::string::npos) << run.output;
  EXPECT_TRUE(fs::exists(d / "agree.png"));
  const auto both = testing_app::runApp("gridtopo-topology-compare",
                                        (d / "a.png").string() + " " + (d / "a").string() + " --reference-topology " +
                                            (d / "b.png").string() + " --reference-topology " + (d / "b").string() +
                                            " --reference-map " + (d / "b.png").string());
  EXPECT_EQ(both.status, 2) << both.output;
}
