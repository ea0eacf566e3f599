// The SLAM variant of the SLAM-like training maps (issue 15, item 1): the SLAM's map of a simulated run, started at
// the true start pose, placed in the plan's pixel lattice; the plan's labels land on the right cells, and a wrong
// start pose puts them on the wrong ones.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "gridtopo/places/occupancy.h"
#include "gridtopo/simtrain/slam_training_map.h"
#include "gridtopo/simtrain/training_map.h"
#include "synthetic_plan.h"

using namespace gridtopo;
using namespace gridtopo::simtrain;

namespace {

TrainingMapOptions slamVariant() {
  TrainingMapOptions o;
  o.variant = MapVariant::Slam;
  o.slam.particles = 8;  // small and fast; the default [slam] otherwise
  o.slam.threads = 1;
  return o;
}

}  // namespace

TEST(SlamTrainingMap, LabelsLandOnTheRightCells) {
  const auto p = test::threeRoomPlan();
  const TrainingMapOptions o = slamVariant();
  const TrainingMap m = simulateTrainingMap(p.grey, p.codes, p.resolution, o);
  ASSERT_EQ(m.grey.size(), p.grey.size());
  ASSERT_EQ(m.slam_trajectory.size(), m.log.truth.size());
  EXPECT_GT(m.slam_processed_scans, 100u);
  // The SLAM keeps close to the truth on this small plan (measured: 298 processed scans, final error 0.049 m,
  // at most 0.10 m, 0.26 degrees).
  EXPECT_LT(m.drift.final_position_error, 0.1);
  EXPECT_LT(m.drift.max_position_error, 0.15);
  EXPECT_LT(m.drift.final_heading_error, 0.01);
  // Its walls are the plan's walls up to that drift: measured 93.6 % of its 3169 occupied cells within one cell of
  // a plan wall (the exact map: >= 99 %, TrainingMap.LabelsLandOnTheRightCells), all within two.
  EXPECT_GT(m.drift.occupied_cells, 3000u);
  EXPECT_GE(m.drift.occupied_within_1, 0.9);
  EXPECT_GE(m.drift.occupied_within_2, 0.995);
  // The labels it takes are those of the places its cells show (measured 99.8 % of 54126 cells).
  EXPECT_GT(m.drift.labelled_free_cells, 30000u);
  EXPECT_GE(m.drift.label_agreement, 0.99);
  // Its free cells are the plan's labelled free cells, like the exact map's.
  const places::OccupancyImage occ = places::occupancyFromGrey(m.grey, p.resolution, "map", 204);
  long map_free = 0, on_labelled = 0;
  for (int r = 0; r < occ.rows(); ++r)
    for (int c = 0; c < occ.cols(); ++c)
      if (occ.cells.at<unsigned char>(r, c) == places::kFree)
        ++map_free, on_labelled += p.grey.at<unsigned char>(r, c) == 255 && p.codes.at<unsigned char>(r, c) != 0;
  EXPECT_GE(static_cast<double>(on_labelled) / map_free, 0.99) << map_free;
}

TEST(SlamTrainingMap, AShiftedStartPosePutsTheLabelsOnWrongCells) {
  const auto p = test::threeRoomPlan();
  TrainingMapOptions o = slamVariant();
  o.variant = MapVariant::Exact;  // the simulated run only; the SLAM is run here
  const TrainingMap exact = simulateTrainingMap(p.grey, p.codes, p.resolution, o);
  const auto& truth = exact.log.truth;
  const cv::Mat plan_free = p.grey == 255;
  const auto slamFrom = [&](mrpt::math::TPose2D start) {
    const SlamTrainingMap s = runSlamInPlanFrame(exact.log, start, p.grey.rows, p.grey.cols, o.slam);
    return measureSlamDrift(s.grey, plan_free, p.codes, p.resolution, s.trajectory, truth);
  };
  const SlamDrift right = slamFrom(truth.front());
  mrpt::math::TPose2D shifted = truth.front();
  shifted.x += 0.4, shifted.y += 0.3, shifted.phi += 0.05;  // 0.5 m and 3 degrees off
  const SlamDrift wrong = slamFrom(shifted);
  EXPECT_GE(right.label_agreement, 0.99);
  EXPECT_GE(right.occupied_within_1, 0.9);
  EXPECT_LT(right.max_position_error, 0.15);
  // The whole map moves with its start: the walls leave the plan's walls, the labels their places (measured: poses
  // up to 1.13 m off, 34.9 % of the occupied cells within one cell of a plan wall, label agreement 88.0 %).
  EXPECT_GT(wrong.max_position_error, 0.5);
  EXPECT_LT(wrong.occupied_within_1, 0.5);
  EXPECT_LT(wrong.label_agreement, 0.93);
}

TEST(SlamTrainingMap, LabelTransferAgreementOfAMapMovedByWholeCells) {
  // A map that is the plan moved 10 cells east, with the SLAM's poses moved with it: every free cell shows the place
  // 10 cells west of it. Agreement = share of the free cells whose label equals the label 10 cells west.
  const auto p = test::threeRoomPlan();
  const double res = p.resolution;
  cv::Mat moved(p.grey.size(), CV_8U, cv::Scalar(128));
  p.grey(cv::Rect(0, 0, p.grey.cols - 10, p.grey.rows)).copyTo(moved(cv::Rect(10, 0, p.grey.cols - 10, p.grey.rows)));
  std::vector<mrpt::math::TPose2D> truth;
  std::vector<TimedPose> slam;
  for (double x = 1.0; x < 15.5; x += 0.5) {  // along the corridor and through every room
    truth.push_back({x, 1.0, 0.0});
    for (double y = 2.0; y < 9.0; y += 0.5) truth.push_back({x, y, 0.0});
  }
  for (const auto& t : truth) slam.push_back({0.0, {t.x + 10 * res, t.y, t.phi}});
  long free = 0, same = 0;
  for (int r = 0; r < moved.rows; ++r)
    for (int c = 10; c < moved.cols; ++c) {
      if (moved.at<unsigned char>(r, c) < 204) continue;
      const int t = p.codes.at<unsigned char>(r, c - 10), l = p.codes.at<unsigned char>(r, c);
      if (t == 0 && l == 0) continue;
      ++free, same += t == l;
    }
  std::size_t labelled = 0;
  const double a = labelTransferAgreement(moved, p.codes, res, slam, truth, &labelled);
  EXPECT_EQ(labelled, static_cast<std::size_t>(free));
  EXPECT_NEAR(a, static_cast<double>(same) / free, 1e-12);
  EXPECT_LT(a, 0.97);  // the moved walls and doors take wrong labels
  // With the SLAM's poses equal to the true ones the measure sees no drift: 1, whatever the map shows (it measures
  // where the SLAM put the cells, not the map's content).
  std::vector<TimedPose> unmoved;
  for (const auto& t : truth) unmoved.push_back({0.0, t});
  EXPECT_DOUBLE_EQ(labelTransferAgreement(moved, p.codes, res, unmoved, truth), 1.0);
}
