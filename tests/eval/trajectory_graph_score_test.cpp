// The graph along the trajectory (trajectory_graph_score.h) on a building drawn on a 5 cm grid: a corridor (plan
// region 4; x 1..19 m, y 8..10 m) with rooms A (1; x 1..6 m) and B (2; x 6.2..12 m) above it through 0.9 m doors,
// and room C (3; x 12.2..19 m) reached from B through a 1.3 m opening (a door of the plan; no door to the
// geometry). The robot drives from A along the corridor into B and on into C.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "gridtopo/eval/trajectory_graph_score.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/pipeline.h"

using namespace gridtopo;
using namespace gridtopo::eval;
using namespace gridtopo::topology;

namespace {

constexpr double kRes = 0.05;
constexpr unsigned char kRoom = 0, kCorridor = 1;

double c(double m) { return m / kRes; }
int ci(double m) { return static_cast<int>(std::lround(m / kRes)); }

struct Building {
  cv::Mat labels;  // the classifier's: rooms and corridor, no doorway
  PlanGraph plan;
};

Building makeBuilding() {
  Building b;
  const cv::Size size(ci(20), ci(11));
  b.labels = cv::Mat(size, CV_8U, cv::Scalar(places::kNoLabel));
  b.plan.regions = cv::Mat::zeros(size, CV_32S);
  const auto box = [&](double x0, double y0, double x1, double y1, unsigned char label, int region) {
    const cv::Rect r(cv::Point(ci(x0), ci(y0)), cv::Point(ci(x1), ci(y1)));
    b.labels(r).setTo(label);
    b.plan.regions(r).setTo(region);
  };
  box(1, 8, 19, 10, kCorridor, 4);
  box(1, 1, 6, 7.8, kRoom, 1);
  box(6.2, 1, 12, 7.8, kRoom, 2);
  box(12.2, 1, 19, 7.8, kRoom, 3);
  box(3, 7.8, 3.9, 8, kRoom, 0);    // door A
  box(9, 7.8, 9.9, 8, kRoom, 0);    // door B
  box(12, 3, 12.2, 4.3, kRoom, 0);  // the opening between B and C
  b.plan.kind = {{1, 0}, {2, 0}, {3, 0}, {4, 1}};
  b.plan.links = {{{1, 4}, true}, {{2, 4}, true}, {{2, 3}, true}};
  return b;
}

std::vector<cv::Point2d> drive() {
  const std::vector<cv::Point2d> corners{{c(3.45), c(4.0)},  {c(3.45), c(8.9)},  {c(9.45), c(8.9)},
                                         {c(9.45), c(6.0)},  {c(10.0), c(3.65)}, {c(15.5), c(3.65)}};
  std::vector<cv::Point2d> out{corners.front()};
  for (std::size_t i = 1; i < corners.size(); ++i)
    for (int k = 1; k <= 50; ++k) out.push_back(corners[i - 1] + (corners[i] - corners[i - 1]) * (k / 50.0));
  return out;
}

TrajectoryGraphScore score(const TopologyResult& t, const PlanGraph& plan) {
  return scoreGraphAlongPath(t.graph, t.regions, plan, drive(), kRes);
}

}  // namespace

TEST(TrajectoryGraphScore, EveryDoorCrossedIsFoundWhenTheGraphHasItsDoorwayNode) {
  const Building b = makeBuilding();
  const TrajectoryGraphScore s = score(buildTopology(b.labels, kRes, {}, nullptr, {0, 0}, drive()), b.plan);
  EXPECT_TRUE(s.has_trajectory);
  EXPECT_EQ(s.region_changes, 3);
  EXPECT_EQ(s.region_changes_through_door, 3);
  ASSERT_EQ(s.doors_crossed, 3);
  EXPECT_EQ(s.doors_with_doorway_node, 3);
  EXPECT_EQ(s.doors_found, 3);
  EXPECT_DOUBLE_EQ(s.doorsFoundFraction(), 1.0);
  // In the order crossed, in the direction crossed.
  EXPECT_EQ(s.doors[0].plan_a, 1);
  EXPECT_EQ(s.doors[0].plan_b, 4);
  EXPECT_EQ(s.doors[1].plan_a, 4);
  EXPECT_EQ(s.doors[1].plan_b, 2);
  EXPECT_EQ(s.doors[2].plan_a, 2);
  EXPECT_EQ(s.doors[2].plan_b, 3);
  for (const DoorCrossed& d : s.doors) EXPECT_EQ(d.crossings, 1);
  // A -> corridor -> B -> C: three node changes, each where the plan changes too.
  EXPECT_EQ(s.node_changes, 3);
  EXPECT_EQ(s.node_changes_scored, 3);
  EXPECT_EQ(s.spurious_splits, 0);
}

TEST(TrajectoryGraphScore, TheOpeningWithoutItsDoorwayNodeIsNotFound) {
  const Building b = makeBuilding();
  // The topology without the path: the geometry's two doors only.
  const TrajectoryGraphScore s = score(buildTopology(b.labels, kRes, {}), b.plan);
  ASSERT_EQ(s.doors_crossed, 3);
  EXPECT_EQ(s.doors_found, 2);
  EXPECT_EQ(s.doors_with_doorway_node, 2);
  EXPECT_FALSE(s.doors[2].found);
  EXPECT_NEAR(s.doorsFoundFraction(), 2.0 / 3.0, 1e-12);
}

TEST(TrajectoryGraphScore, ARoomLabelInTheCorridorIsASpuriousSplit) {
  Building b = makeBuilding();
  // The classifier calls the corridor's west end (x 1..7 m) room: along the corridor, room then corridor.
  b.labels(cv::Rect(cv::Point(ci(1), ci(8)), cv::Point(ci(7), ci(10)))).setTo(kRoom);
  const TrajectoryGraphScore s = score(buildTopology(b.labels, kRes, {}, nullptr, {0, 0}, drive()), b.plan);
  EXPECT_EQ(s.spurious_splits, 1);
  EXPECT_EQ(s.spurious_label_changes, 1);
  EXPECT_EQ(s.spurious_boundaries, 1);
  EXPECT_EQ(s.node_changes, 4);
}

TEST(TrajectoryGraphScore, NoTrajectoryNoScore) {
  const Building b = makeBuilding();
  const TopologyResult t = buildTopology(b.labels, kRes, {});
  const TrajectoryGraphScore s = scoreGraphAlongPath(t.graph, t.regions, b.plan, {}, kRes);
  EXPECT_FALSE(s.has_trajectory);
  EXPECT_EQ(s.doors_crossed, 0);
  EXPECT_EQ(s.node_changes, 0);
  EXPECT_NE(s.toJson().find("\"has_trajectory\": false"), std::string::npos);
}
