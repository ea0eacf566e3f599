// The simulated SLAM-like training maps of issue 15 as the trainer reads them ([training] simulated_maps).
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "common/scratch.h"
#include "gridtopo/core/error.h"
#include "gridtopo/places/training.h"

using namespace gridtopo;
using namespace gridtopo::places;

TEST(SimulatedMaps, ReadAsASlamGridWithThePlansLabels) {
  const auto dir = test::scratch("sim");
  // A 20 x 20 plan's labels: room on the left half, corridor on the right.
  cv::Mat codes(20, 20, CV_8U, cv::Scalar(77));
  codes.colRange(10, 20).setTo(115);
  cv::imwrite((dir / "labels.png").string(), codes);
  // Its simulated map: 230 (free for the SLAM threshold 204, not for the plans' 250), a wall row, unknown corner,
  // and one free cell alone in the unknown (removed by the opening).
  cv::Mat grey(20, 20, CV_8U, cv::Scalar(230));
  grey.row(10).setTo(0);
  grey(cv::Rect(14, 14, 6, 6)).setTo(128);
  grey.at<unsigned char>(17, 17) = 255;
  cv::imwrite((dir / "Plan_sim_map.png").string(), grey);
  LabelledMapFiles files{"Plan", (dir / "labels.png").string(), "", "", ""};
  TrainingOptions o;
  EXPECT_FALSE(loadSimulatedLabelledMap(files, o, 0.05));  // simulated_maps empty: off
  o.simulated_maps = dir.string();
  const auto m = loadSimulatedLabelledMap(files, o, 0.05);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->name, "Plan_sim");
  EXPECT_EQ(cv::countNonZero(m->codes != codes), 0);  // the plan's labels, cell for cell
  EXPECT_EQ(m->occ.cells.at<unsigned char>(2, 2), kFree);
  EXPECT_EQ(m->occ.cells.at<unsigned char>(10, 5), kOccupied);
  EXPECT_EQ(m->occ.cells.at<unsigned char>(15, 15), kUnknown);
  EXPECT_EQ(m->occ.cells.at<unsigned char>(17, 17), kUnknown);  // opened away
  // No simulated map for this name: nothing.
  files.name = "Other";
  EXPECT_FALSE(loadSimulatedLabelledMap(files, o, 0.05));
  // A map of another size than its plan is refused, naming the map.
  files.name = "Plan";
  cv::imwrite((dir / "Plan_sim_map.png").string(), cv::Mat(21, 20, CV_8U, cv::Scalar(230)));
  try {
    loadSimulatedLabelledMap(files, o, 0.05);
    FAIL() << "size mismatch accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.file().find("Plan_sim_map.png"), std::string::npos);
  }
}

TEST(SimulatedMaps, TrainingIniNamesAMissingDirectory) {
  const auto dir = test::scratch("ini");
  const auto ini = (dir / "train.ini").string();
  std::ofstream(ini) << "[training]\nsimulated_maps = " << (dir / "nowhere").string() << "\n";
  try {
    loadTrainingConfig(ini);
    FAIL() << "missing directory accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), ini);
    EXPECT_NE(e.field().find("simulated_maps"), std::string::npos);
  }
  std::ofstream(ini) << "[training]\nsimulated_maps = " << dir.string() << "\nsimulated_free_threshold = 204\n"
                     << "[scan_simulation]\nunknown_cells = max_range\n";
  const auto c = loadTrainingConfig(ini);
  EXPECT_EQ(c.training.simulated_maps, dir.string());
  EXPECT_EQ(c.scan.unknown_cells, BeamStop::kMaxRange);
  std::ofstream(ini) << "[scan_simulation]\nmap_border = pass\n";
  EXPECT_THROW(loadTrainingConfig(ini), InputError);
}

TEST(SimulatedMaps, ShippedTrainingIniKeepsTheDefaults) {
  const auto c = loadTrainingConfig(std::string(GRIDTOPO_SOURCE_DIR) + "/config-ini/topology_train.ini");
  EXPECT_TRUE(c.training.simulated_maps.empty());
  EXPECT_EQ(c.training.simulated_free_threshold, 204);
  EXPECT_DOUBLE_EQ(c.training.simulated_free_opening_radius, 0.05);
  EXPECT_EQ(c.scan.unknown_cells, BeamStop::kObstacle);
  EXPECT_EQ(c.scan.map_border, BeamStop::kObstacle);
}
