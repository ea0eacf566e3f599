// A room the robot travels through is a corridor (thoroughfares.h), on buildings drawn on a 5 cm grid with the labels
// a classifier might give them.
#include <gtest/gtest.h>

#include "common/drawn_building.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/topology/thoroughfares.h"

using namespace gridtopo;
using namespace gridtopo::topology;
using namespace gridtopo::test::drawn;

namespace {

constexpr unsigned char kRoom = 0, kCorridor = 1;

unsigned char labelAt(const cv::Mat& labels, double x, double y) { return labels.at<unsigned char>(ci(y), ci(x)); }

// Two corridors (x 1..3 m and 17..19 m, y 1..14 m) with a 14 m x 11 m hall between them (x 3..17 m, y 2..13 m) that
// the classifier reads as room, and an office east of the east corridor (x 19..23 m, y 4..8 m). A strip of 0.3 m
// without a label (a row of pillars) runs across the hall's south half (x 9.85..10.15 m, y 2..9 m).
cv::Mat building() {
  cv::Mat labels(ci(22), ci(24), CV_8U, cv::Scalar(places::kNoLabel));
  box(labels, 1, 1, 3, 14, kCorridor);
  box(labels, 17, 1, 19, 14, kCorridor);
  box(labels, 3, 2, 17, 13, kRoom);
  box(labels, 9.85, 2, 10.15, 9, places::kNoLabel);
  box(labels, 19, 4, 23, 8, kRoom);
  return labels;
}

// Up the west corridor and across the hall three times (a snake), ending in the east corridor.
std::vector<cv::Point2d> snake() {
  return poses({{2, 1.5}, {2, 3}, {18, 3}, {18, 7.5}, {2, 7.5}, {2, 12}, {18, 12}, {18, 13.5}});
}

// Into the office from the east corridor and back out through the same side, four times.
std::vector<cv::Point2d> officeVisits() {
  std::vector<cv::Point2d> corners{{18, 4.5}};
  for (int k = 0; k < 4; ++k) {
    const double y = 5 + 0.5 * k;
    corners.insert(corners.end(), {{18, y}, {22, y}, {22, y + 0.4}, {18, y + 0.4}});
  }
  return poses(corners);
}

}  // namespace

TEST(Thoroughfares, AHallCrossedAgainAndAgainBecomesCorridor) {
  const cv::Mat labels = building();
  std::vector<Thoroughfare> found;
  const cv::Mat out = relabelThoroughfares(labels, snake(), kRes, ThoroughfareOptions{}, &found);
  ASSERT_EQ(found.size(), 1u);
  // Three crossings; the pillars' strip (0.3 m off every region) does not cut a crossing in two.
  EXPECT_EQ(found[0].crossings, 3);
  EXPECT_EQ(found[0].openings, 6);  // in and out at y 3, 7.5 and 12 m on both sides
  EXPECT_NEAR(found[0].area_m2, 14 * 11 - 0.3 * 7, 0.5);
  EXPECT_EQ(labelAt(out, 5, 5), kCorridor);
  EXPECT_EQ(labelAt(out, 12, 12), kCorridor);
  EXPECT_EQ(labelAt(out, 10, 5), places::kNoLabel);  // the strip stays unlabelled
  EXPECT_EQ(labelAt(out, 21, 6), kRoom);             // the office the path never entered
  EXPECT_EQ(labelAt(out, 2, 5), kCorridor);
  // Fewer crossings than asked for: the hall stays room.
  ThoroughfareOptions four;
  four.min_crossings = 4;
  EXPECT_EQ(cv::countNonZero(relabelThoroughfares(labels, snake(), kRes, four) != labels), 0);
  // Offices joined to the hall in one room region (x 3..17 m, y 13..21 m, read as room too, the walls between them not
  // mapped): the path never comes near most of their cells, so the region is not a thoroughfare (coverage).
  cv::Mat joined = labels.clone();
  box(joined, 3, 13, 17, 21, kRoom);
  std::vector<Thoroughfare> none;
  EXPECT_EQ(cv::countNonZero(relabelThoroughfares(joined, snake(), kRes, ThoroughfareOptions{}, &none) != joined), 0);
  EXPECT_TRUE(none.empty());
  // The hall alone: 0.85-0.9 of its cells lie within 2 m of the path.
  EXPECT_GT(found[0].coverage, 0.85);
  EXPECT_LT(found[0].coverage, 0.95);
  // Off, or without a path: a copy.
  ThoroughfareOptions off;
  off.enabled = false;
  EXPECT_EQ(cv::countNonZero(relabelThoroughfares(labels, snake(), kRes, off) != labels), 0);
  EXPECT_EQ(cv::countNonZero(relabelThoroughfares(labels, {}, kRes, ThoroughfareOptions{}) != labels), 0);
}

TEST(Thoroughfares, ARoomEnteredAndLeftThroughOneSideStaysRoom) {
  const cv::Mat labels = building();
  std::vector<Thoroughfare> found;
  // Four visits that each go 3 m into the office, but enter and leave within 0.4 m of each other: no crossing.
  const cv::Mat out = relabelThoroughfares(labels, officeVisits(), kRes, ThoroughfareOptions{}, &found);
  EXPECT_TRUE(found.empty());
  EXPECT_EQ(cv::countNonZero(out != labels), 0);
  // A long span alone is no crossing either: the trajectory starting in the hall and leaving it, or with a gap in
  // it (a jump of more than 3 m between two poses), does not count the piece before or after.
  std::vector<cv::Point2d> from_inside = poses({{10, 12}, {18, 12}, {18, 3}, {2, 3}, {2, 7.5}, {18, 7.5}});
  EXPECT_TRUE(relabelThoroughfares(labels, from_inside, kRes, ThoroughfareOptions{}, &found).data);
  EXPECT_TRUE(found.empty()) << found.size();  // crossings at y 3 and 7.5 only: 2 < 3
  std::vector<cv::Point2d> gap = poses({{2, 3}, {18, 3}, {18, 7.5}, {2, 7.5}, {2, 12}, {8, 12}});
  const std::vector<cv::Point2d> rest = poses({{12, 12}, {18, 12}, {18, 13.5}});  // jumped 4 m inside the hall
  gap.insert(gap.end(), rest.begin(), rest.end());
  relabelThoroughfares(labels, gap, kRes, ThoroughfareOptions{}, &found);
  EXPECT_TRUE(found.empty()) << found.size();
}

TEST(Thoroughfares, TheTopologyWithThePathHasTheHallAsACorridor) {
  const cv::Mat labels = building();
  TopologyOptions o;
  const TopologyResult with = buildTopology(labels, kRes, o, nullptr, {0, 0}, snake());
  ASSERT_EQ(with.thoroughfares.size(), 1u);
  EXPECT_EQ(labelAt(with.labels, 12, 5), kCorridor);
  o.thoroughfares.enabled = false;
  const TopologyResult without = buildTopology(labels, kRes, o, nullptr, {0, 0}, snake());
  EXPECT_TRUE(without.thoroughfares.empty());
  EXPECT_EQ(labelAt(without.labels, 12, 5), kRoom);
  // Without a path the step does nothing.
  const TopologyResult no_path = buildTopology(labels, kRes, TopologyOptions{}, nullptr, {0, 0}, {});
  EXPECT_EQ(labelAt(no_path.labels, 12, 5), kRoom);
}
