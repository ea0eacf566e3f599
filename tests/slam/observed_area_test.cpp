// What a stretch of scans saw (observed_area.h): free space along the beams, the hits and a cell around them seen,
// everything behind the walls and out of the beams' reach unseen; a match is scored on the query points the place
// saw, and a look-alike whose walls stand in the place's free space is caught by its contradiction.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "gridtopo/slam/observed_area.h"

using namespace gridtopo;

namespace {

// A 10 x 6 m room's walls (every 5 cm) in the frame of a robot at its centre.
std::vector<slam::Point2> roomWalls() {
  std::vector<slam::Point2> pts;
  for (double x = -5; x <= 5 + 1e-9; x += 0.05) {
    pts.push_back({x, -3});
    pts.push_back({x, 3});
  }
  for (double y = -3; y <= 3 + 1e-9; y += 0.05) {
    pts.push_back({-5, y});
    pts.push_back({5, y});
  }
  return pts;
}

// The room seen by one scan from its centre: the robot 0.2 m west of it, its laser 0.2 m ahead (the area keeps no
// reference to the hits).
slam::ObservedArea roomArea(const std::vector<slam::Point2>& walls) {
  std::vector<slam::Point2> hits;  // robot frame
  for (const auto& p : walls) hits.push_back({p.x + 0.2, p.y});
  return slam::ObservedArea({{slam::Pose2{-0.2, 0.0, 0.0}, {0.2, 0.0}, &hits}}, 0.1, 0.3, 0.2);
}

}  // namespace

TEST(ObservedArea, TheBeamsSeeFreeSpaceTheWallsAreSeenAndWhatLiesBehindThemIsNot) {
  const slam::ObservedArea area = roomArea(roomWalls());
  // Inside the room: seen and free, up to the last 0.3 m before a wall.
  EXPECT_TRUE(area.seen({0.0, 0.0}));
  EXPECT_TRUE(area.seenFree({0.0, 0.0}));
  EXPECT_TRUE(area.seenFree({3.0, 1.5}));
  EXPECT_TRUE(area.seenFree({-4.5, 0.0}));
  EXPECT_FALSE(area.seenFree({4.85, 0.0}));
  // The wall, and just behind it: seen (a thin wall's far face is in view), not free.
  EXPECT_TRUE(area.seen({5.0, 0.0}));
  EXPECT_FALSE(area.seenFree({5.0, 0.0}));
  EXPECT_TRUE(area.seen({5.08, 0.0}));
  // Behind the walls and far away: not seen.
  EXPECT_FALSE(area.seen({6.0, 0.0}));
  EXPECT_FALSE(area.seen({0.0, 4.0}));
  EXPECT_FALSE(area.seen({40.0, 40.0}));
  EXPECT_FALSE(area.seenFree({6.0, 0.0}));
}

TEST(ObservedArea, AMatchIsScoredWhereThePlaceLookedAndALookAlikeInItsFreeSpaceIsContradicted) {
  const std::vector<slam::Point2> walls = roomWalls();
  const slam::ObservedArea area = roomArea(walls);
  const slam::CorrelationGrid grid(walls, 0.05, 0.07, 7, 0.03);

  // The room itself: every point seen, high, none contradicted.
  const slam::MatchEvidence same = slam::matchEvidence(grid, area, walls, {});
  EXPECT_GT(same.coverage, 0.99);
  EXPECT_GT(same.observed_score, 0.85);  // the grid's value interpolated between cells
  EXPECT_LT(same.contradiction, 0.01);

  // The room and, beyond its east wall, a second room the place never saw: the plain mean falls by half, the mean
  // over the observed points does not, and nothing is contradicted.
  std::vector<slam::Point2> two_rooms = walls;
  for (const auto& p : walls) two_rooms.push_back({p.x + 10.4, p.y});
  const slam::MatchEvidence beyond = slam::matchEvidence(grid, area, two_rooms, {});
  EXPECT_NEAR(beyond.coverage, 0.5, 0.05);
  EXPECT_NEAR(beyond.observed_score, same.observed_score, 0.01);
  EXPECT_LT(beyond.contradiction, 0.01);

  // A look-alike: the same room shifted 1.5 m east. Its west wall stands where the place's beams passed.
  const slam::MatchEvidence shifted = slam::matchEvidence(grid, area, walls, {1.5, 0.0, 0.0});
  EXPECT_GT(shifted.contradiction, 0.15);  // 0.17: its west wall, a fifth of its points
  EXPECT_LT(shifted.observed_score, 0.75);

  // An empty query and an empty area give nothing.
  EXPECT_EQ(slam::matchEvidence(grid, area, {}, {}).coverage, 0.0);
  const slam::ObservedArea none({}, 0.1, 0.3, 0.2);
  EXPECT_FALSE(none.seen({0.0, 0.0}));
  const slam::MatchEvidence blind = slam::matchEvidence(grid, none, walls, {});
  EXPECT_EQ(blind.coverage, 0.0);
  EXPECT_EQ(blind.observed_score, 0.0);
  EXPECT_EQ(blind.contradiction, 0.0);
}
