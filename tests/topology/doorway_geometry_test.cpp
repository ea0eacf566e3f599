// Doorways from geometry (doorway_geometry.h): a corridor with doors of 0.8 m and 1.0 m onto two rooms, a niche in
// the corridor wall and a wide opening. The classifier's labels are simulated: it labels the 1.0 m door and misses
// the 0.8 m one, and it calls a stretch of the straight corridor wall a doorway.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "gridtopo/places/labelling.h"
#include "gridtopo/topology/doorway_geometry.h"
#include "gridtopo/topology/graph.h"
#include "gridtopo/topology/pipeline.h"

using namespace gridtopo;
using namespace gridtopo::topology;

namespace {

constexpr double kRes = 0.05;
constexpr unsigned char kRoom = 0, kCorridor = 1, kDoor = 2;

// Metres to cells; y grows downwards in the image. The corridor: x 1..19 m, y 6..8 m. Its north wall (y 5.8..6)
// has the 0.8 m door at x 4..4.8 onto room A (x 2..8, y 1..5.8) and the 1.0 m door at x 12..13 onto room B
// (x 10..16, y 1..5.8); its south wall (y 8..8.2) has a niche 1.0 m wide and 0.6 m deep at x 9..10.
int c(double m) { return static_cast<int>(std::lround(m / kRes)); }

struct World {
  cv::Mat free;    // 255 = free
  cv::Mat labels;  // the simulated classifier's
};

World makeWorld() {
  World w;
  w.free = cv::Mat::zeros(c(10), c(20), CV_8U);
  auto box = [&](double x0, double y0, double x1, double y1) {
    cv::rectangle(w.free, cv::Point(c(x0), c(y0)), cv::Point(c(x1) - 1, c(y1) - 1), cv::Scalar(255), cv::FILLED);
  };
  box(1, 6, 19, 8);           // corridor
  box(2, 1, 8, 5.8);          // room A
  box(10, 1, 16, 5.8);        // room B
  box(4, 5.8, 4.8, 6);        // door A, 0.8 m
  box(12, 5.8, 13, 6);        // door B, 1.0 m
  box(9, 8, 10, 8.6);         // niche
  w.labels = cv::Mat(w.free.size(), CV_8U, cv::Scalar(places::kNoLabel));
  w.labels.setTo(kCorridor, w.free);
  cv::Mat rooms = cv::Mat::zeros(w.free.size(), CV_8U);
  cv::rectangle(rooms, cv::Point(c(2), c(1)), cv::Point(c(8) - 1, c(5.8) - 1), cv::Scalar(255), cv::FILLED);
  cv::rectangle(rooms, cv::Point(c(10), c(1)), cv::Point(c(16) - 1, c(5.8) - 1), cv::Scalar(255), cv::FILLED);
  w.labels.setTo(kRoom, rooms);
  // The classifier finds door B (and a little of the corridor in front of it), misses door A, and calls a stretch
  // of the straight south wall (x 15..16) a doorway.
  cv::rectangle(w.labels, cv::Point(c(12), c(5.8)), cv::Point(c(13) - 1, c(6.2) - 1), cv::Scalar(kDoor), cv::FILLED);
  cv::rectangle(w.labels, cv::Point(c(15), c(7.6)), cv::Point(c(16) - 1, c(8) - 1), cv::Scalar(kDoor), cv::FILLED);
  return w;
}

int doorCellsIn(const cv::Mat& labels, double x0, double y0, double x1, double y1) {
  return cv::countNonZero(labels(cv::Rect(cv::Point(c(x0), c(y0)), cv::Point(c(x1), c(y1)))) == kDoor);
}

}  // namespace

TEST(DoorwayGeometry, BothDoorsAreCriticalLinesTheNicheAndTheWallAreNot) {
  const World w = makeWorld();
  const std::vector<CriticalLine> lines = findDoorways(w.free, kRes, DoorwayGeometryOptions{});
  ASSERT_EQ(lines.size(), 2u);
  // Row-major order of the critical points: both lie in the north wall's gap, A then B by x.
  EXPECT_NEAR(lines[0].width, 0.8, 0.051);
  EXPECT_NEAR(lines[1].width, 1.0, 0.051);
  EXPECT_NEAR(lines[0].centre.x * kRes, 4.4, 0.1);
  EXPECT_NEAR(lines[1].centre.x * kRes, 12.5, 0.1);
  for (const CriticalLine& l : lines) EXPECT_NEAR(l.centre.y * kRes, 5.9, 0.15);
  // A door narrower than the narrowest allowed is none.
  DoorwayGeometryOptions narrow;
  narrow.max_width = 0.7;
  EXPECT_TRUE(findDoorways(w.free, kRes, narrow).empty());
}

// The lines are found over the box of the places: the same world in a large empty map (and touching its border)
// gives the same lines, moved by its offset.
TEST(DoorwayGeometry, LinesDoNotDependOnTheEmptyMapAroundThePlaces) {
  const World w = makeWorld();
  const std::vector<CriticalLine> tight = findDoorways(w.free, kRes, DoorwayGeometryOptions{});
  ASSERT_EQ(tight.size(), 2u);
  for (const cv::Point off : {cv::Point(913, 407), cv::Point(0, 0)}) {
    cv::Mat big = cv::Mat::zeros(w.free.rows + 700, w.free.cols + 1100, CV_8U);
    w.free.copyTo(big(cv::Rect(off, w.free.size())));
    const std::vector<CriticalLine> wide = findDoorways(big, kRes, DoorwayGeometryOptions{});
    ASSERT_EQ(wide.size(), tight.size());
    for (std::size_t i = 0; i < tight.size(); ++i) {
      EXPECT_EQ(wide[i].a, tight[i].a + cv::Point2d(off));
      EXPECT_EQ(wide[i].b, tight[i].b + cv::Point2d(off));
      EXPECT_EQ(wide[i].centre, tight[i].centre + off);
      EXPECT_EQ(wide[i].width, tight[i].width);
    }
  }
  EXPECT_TRUE(findDoorways(cv::Mat::zeros(50, 60, CV_8U), kRes, DoorwayGeometryOptions{}).empty());  // no place
}

TEST(DoorwayGeometry, TheMissedDoorBecomesTheDoorwayNodeBetweenItsRoomAndTheCorridor) {
  const World w = makeWorld();
  TopologyOptions o;
  o.doorways.enabled = false;
  const TopologyResult without = buildTopology(w.labels, kRes, o);
  o.doorways.enabled = true;
  const TopologyResult with = buildTopology(w.labels, kRes, o);
  EXPECT_EQ(doorCellsIn(without.labels, 4, 5.8, 4.8, 6), 0);
  EXPECT_GT(doorCellsIn(with.labels, 4, 5.8, 4.8, 6), 40);  // the 0.8 m door, 0.2 m deep: 64 cells
  // Every room is attached to the corridor through a doorway node, and no room touches the corridor directly.
  const TopologicalGraph& g = with.graph;
  int rooms = 0, doorways = 0;
  for (const auto& n : g.nodes) {
    rooms += n.label == kRoom;
    doorways += n.label == kDoor;
  }
  EXPECT_EQ(rooms, 2);
  for (const auto& n : g.nodes) {
    if (n.label != kRoom) continue;
    bool via_door = false;
    for (const auto& e : g.edges) {
      if (e.a != n.id && e.b != n.id) continue;
      const GraphNode* other = g.node(e.a == n.id ? e.b : e.a);
      ASSERT_NE(other, nullptr);
      EXPECT_NE(other->label, kCorridor) << "room " << n.id << " touches the corridor without a doorway";
      via_door |= other->label == kDoor;
    }
    EXPECT_TRUE(via_door) << "room " << n.id;
  }
  // The niche is no doorway.
  EXPECT_EQ(doorCellsIn(with.labels, 9, 8, 10, 8.6), 0);
}

TEST(DoorwayGeometry, AClassifierDoorwayAlongAStraightWallIsRefusedWhenAsked) {
  const World w = makeWorld();
  DoorwayGeometryOptions o;
  EXPECT_GT(doorCellsIn(addGeometricDoorways(w.labels, kRes, o), 15, 7.6, 16, 8), 0);  // kept by default
  o.refuse_unsupported = true;
  const cv::Mat refused = addGeometricDoorways(w.labels, kRes, o);
  EXPECT_EQ(doorCellsIn(refused, 15, 7.6, 16, 8), 0);
  EXPECT_EQ(cv::countNonZero(refused(cv::Rect(c(15), c(7.6), c(1), c(0.4))) == kCorridor), c(1) * c(0.4));
  // The supported classifier doorway (door B) stays.
  EXPECT_GT(doorCellsIn(refused, 12, 5.8, 13, 6), 0);
}
