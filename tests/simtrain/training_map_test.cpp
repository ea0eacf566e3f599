#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "gridtopo/places/occupancy.h"
#include "gridtopo/sim/grid_plan.h"
#include "gridtopo/simtrain/plan_tour.h"
#include "gridtopo/simtrain/training_map.h"
#include "synthetic_plan.h"

using namespace gridtopo;
using namespace gridtopo::simtrain;

TEST(GridPlan, RayCastStopsAtTheFirstBlockedCell) {
  // 10 x 10 cells of 0.1 m; column 7 blocked; the top-left cell blocked.
  std::vector<std::uint8_t> b(100, 0);
  for (int r = 0; r < 10; ++r) b[static_cast<std::size_t>(r) * 10 + 7] = 1;
  b[0] = 1;
  const sim::GridPlan g(10, 10, 0.1, b);
  EXPECT_NEAR(g.rayCast(0.25, 0.55, 0.0), 0.45, 1e-9);               // to x = 0.7
  EXPECT_TRUE(std::isinf(g.rayCast(0.25, 0.55, M_PI)));              // leaves the grid at x = 0
  EXPECT_NEAR(g.rayCast(0.25, 0.55, M_PI / 4), 0.45 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(g.rayCast(0.05, 0.55, M_PI / 2), 0.35, 1e-9);          // the top-left cell: row 0 = y in [0.9, 1)
  EXPECT_EQ(g.rayCast(0.75, 0.55, 1.0), 0.0);                         // starts in a blocked cell
}

TEST(PlanTour, EntersEveryRoomThroughItsDoor) {
  const auto p = test::threeRoomPlan();
  TourOptions o;
  const Tour t = planTour(p.grey, p.codes, p.resolution, o);
  EXPECT_EQ(t.rooms, 3);
  EXPECT_EQ(t.rooms_entered, 3);
  EXPECT_EQ(t.rooms_unreachable, 0);
  EXPECT_GE(t.corridor_goals, 5);  // the 16 m corridor in 3 m squares
  for (bool e : t.room_entered) EXPECT_TRUE(e);
  // The path stays on free cells, and reaches every room and both corridor ends.
  int in_room[4] = {0, 0, 0, 0};
  int min_col = 1 << 20, max_col = -1;
  for (const cv::Point& c : t.cells) {
    ASSERT_EQ(p.grey.at<unsigned char>(c), 255);
    ++in_room[t.room_ids.at<int>(c)];
    if (p.codes.at<unsigned char>(c) == 115) min_col = std::min(min_col, c.x), max_col = std::max(max_col, c.x);
  }
  for (int id = 1; id <= 3; ++id) EXPECT_GT(in_room[id], 40) << "room " << id;
  EXPECT_LT(min_col, 40);
  EXPECT_GT(max_col, 290);
  EXPECT_GT(t.waypoints.size(), 6u);
  EXPECT_GT(t.length, 30.0);
  // With probability 0 no room is entered (they are still counted).
  o.room_visit_probability = 0;
  const Tour none = planTour(p.grey, p.codes, p.resolution, o);
  EXPECT_EQ(none.rooms, 3);
  EXPECT_EQ(none.rooms_entered, 0);
}

TEST(TrainingMap, LabelsLandOnTheRightCells) {
  const auto p = test::threeRoomPlan();
  TrainingMapOptions o;
  const TrainingMap m = simulateTrainingMap(p.grey, p.codes, p.resolution, o);
  ASSERT_EQ(m.grey.size(), p.grey.size());
  // The map read as the topology reads a SLAM grid (free >= 204, occupied <= 50).
  const places::OccupancyImage occ = places::occupancyFromGrey(m.grey, p.resolution, "map", 204);
  cv::Mat near_wall;  // plan walls grown by one pixel
  cv::dilate(p.grey == 0, near_wall, cv::Mat::ones(3, 3, CV_8U));
  long map_free = 0, map_free_on_plan_free = 0, map_occ = 0, map_occ_on_plan_wall = 0, map_occ_near_wall = 0;
  long labelled = 0, labelled_known_free = 0;
  for (int r = 0; r < occ.rows(); ++r)
    for (int c = 0; c < occ.cols(); ++c) {
      const bool plan_free = p.grey.at<unsigned char>(r, c) == 255;
      const auto s = occ.cells.at<unsigned char>(r, c);
      if (s == places::kFree) ++map_free, map_free_on_plan_free += plan_free;
      if (s == places::kOccupied)
        ++map_occ, map_occ_on_plan_wall += !plan_free, map_occ_near_wall += near_wall.at<unsigned char>(r, c) != 0;
      if (plan_free && p.codes.at<unsigned char>(r, c) != 0) ++labelled, labelled_known_free += s == places::kFree;
    }
  // Pixel-aligned: free map cells are the plan's free cells (their labels are the plan's), walls its walls. A beam
  // ends in the cell that holds its noisy end point, which for a wall's surface is the wall cell or the free cell
  // in front of it about equally often: every occupied map cell lies within one pixel of a plan wall, more than
  // half on one.
  EXPECT_GE(static_cast<double>(map_free_on_plan_free) / map_free, 0.995) << map_free;
  EXPECT_GE(static_cast<double>(map_occ_near_wall) / map_occ, 0.99) << map_occ;
  EXPECT_GE(static_cast<double>(map_occ_on_plan_wall) / map_occ, 0.5) << map_occ;
  // Every room entered: most of the labelled free space is known free (not the cells along the walls).
  EXPECT_GE(static_cast<double>(labelled_known_free) / labelled, 0.8);
  // SLAM artefacts: unknown space remains (outside the building's walls, behind them).
  EXPECT_GT(cv::countNonZero(occ.cells == places::kUnknown), 1000);
}

TEST(TrainingMap, DeterministicForASeed) {
  const auto p = test::threeRoomPlan();
  TrainingMapOptions o;
  o.tour.room_visit_probability = 0.5;
  const TrainingMap a = simulateTrainingMap(p.grey, p.codes, p.resolution, o);
  const TrainingMap b = simulateTrainingMap(p.grey, p.codes, p.resolution, o);
  EXPECT_EQ(cv::countNonZero(a.grey != b.grey), 0);
  EXPECT_EQ(a.tour.room_entered, b.tour.room_entered);
  o.laser.seed = 2;
  const TrainingMap c = simulateTrainingMap(p.grey, p.codes, p.resolution, o);
  EXPECT_GT(cv::countNonZero(a.grey != c.grey), 100);  // other noise, other map
}
