// One node per open space the robot crossed (open_spaces.h), on buildings drawn on a 5 cm grid with the labels a
// classifier might give them.
#include <gtest/gtest.h>

#include <set>

#include "common/drawn_building.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/open_spaces.h"
#include "gridtopo/topology/pipeline.h"

using namespace gridtopo;
using namespace gridtopo::topology;
using namespace gridtopo::test::drawn;

namespace {

constexpr unsigned char kRoom = 0, kCorridor = 1, kDoor = 2;

// The graph's nodes whose anchor lies in the box (metres).
std::vector<GraphNode> nodesIn(const TopologicalGraph& g, double x0, double y0, double x1, double y1) {
  std::vector<GraphNode> out;
  for (const GraphNode& n : g.nodes) {
    const double x = (n.anchor_px.x + 0.5) * kRes, y = (n.anchor_px.y + 0.5) * kRes;
    if (x >= x0 && x < x1 && y >= y0 && y < y1) out.push_back(n);
  }
  return out;
}

// A corridor (x 2..4 m, y 1..13 m) and, east of it through a 0.9 m door in a 0.2 m wall (x 4..4.2 m, y 6.5..7.4
// m), a hall 15 m x 10 m (x 4.2..19.2 m, y 2..12 m) that the classifier reads as five stripes across it, `first`
// and the other label alternating, 4, 3, 2, 3 and 3 m wide from the west.
cv::Mat hall(unsigned char first) {
  const unsigned char other = first == kRoom ? kCorridor : kRoom;
  cv::Mat labels(ci(14), ci(20.5), CV_8U, cv::Scalar(places::kNoLabel));
  box(labels, 2, 1, 4, 13, kCorridor);
  box(labels, 4, 6.5, 4.2, 7.4, kCorridor);  // the door's cells
  const double edges[] = {4.2, 8.2, 11.2, 13.2, 16.2, 19.2};
  for (int i = 0; i < 5; ++i) box(labels, edges[i], 2, edges[i + 1], 12, i % 2 == 0 ? first : other);
  return labels;
}

// Down the corridor, through the door, across the hall to its east end, back west along its north side, and out
// through the door again.
std::vector<cv::Point2d> crossTheHall() {
  return poses({{3, 2}, {3, 6.95}, {18.5, 6.95}, {18.5, 10.5}, {5.5, 10.5}, {5.5, 6.95}, {3, 6.95}, {3, 12}});
}

constexpr double kHall[] = {4.2, 2, 19.2, 12};

// The defaults with the open spaces on (off by default).
TopologyOptions on() {
  TopologyOptions o;
  o.open_spaces.enabled = true;
  return o;
}

}  // namespace

TEST(OpenSpaces, ALargeOpenHallTheRobotCrossesIsOneNode) {
  const cv::Mat labels = hall(kRoom);
  const std::vector<cv::Point2d> path = crossTheHall();
  const TopologyOptions off;  // the default
  EXPECT_FALSE(off.open_spaces.enabled);
  const TopologyResult before = buildTopology(labels, kRes, off, nullptr, {0, 0}, path);
  // Off: five alternating room / corridor nodes in the hall (and the room entries' doorways between them).
  const std::vector<GraphNode> pieces = nodesIn(before.graph, kHall[0], kHall[1], kHall[2], kHall[3]);
  int places = 0;
  for (const GraphNode& n : pieces) places += n.label != kDoor;
  EXPECT_EQ(places, 5);
  EXPECT_TRUE(before.open_spaces.empty());

  const TopologyResult after = buildTopology(labels, kRes, on(), nullptr, {0, 0}, path);
  ASSERT_EQ(after.open_spaces.size(), 1u);
  EXPECT_EQ(after.open_spaces[0].pieces, 5);
  EXPECT_EQ(after.open_spaces[0].relabelled, 2);
  EXPECT_EQ(after.open_spaces[0].label, kRoom);  // rooms 9 m of the hall's 15, corridor 6
  EXPECT_NEAR(after.open_spaces[0].area_m2, 150, 1);
  EXPECT_NEAR(after.open_spaces[0].relabelled_m2, 60, 1);
  const std::vector<GraphNode> hall_nodes = nodesIn(after.graph, kHall[0], kHall[1], kHall[2], kHall[3]);
  ASSERT_EQ(hall_nodes.size(), 1u);  // one node, no doorway inside the hall
  EXPECT_EQ(hall_nodes[0].label, kRoom);
  EXPECT_NEAR(hall_nodes[0].area_m2, 150, 1);
  // The hall's cells are all room; the door the robot went through is the doorway between hall and corridor.
  const cv::Rect inner(ci(4.5), ci(2), ci(14.7), ci(10));
  EXPECT_EQ(cv::countNonZero(after.labels(inner) == kRoom), inner.area());
  EXPECT_EQ(after.door_passages.size(), 1u);
  EXPECT_EQ(after.graph.nodes.size(), 3u);  // corridor, doorway, hall
  EXPECT_EQ(after.graph.edges.size(), 2u);
}

TEST(OpenSpaces, TheHallTakesTheLabelOfTheLargerArea) {
  // The same stripes with the labels swapped: corridor 9 m of 15, room 6 m, though the rooms are two pieces of five.
  const TopologyResult r = buildTopology(hall(kCorridor), kRes, on(), nullptr, {0, 0}, crossTheHall());
  ASSERT_EQ(r.open_spaces.size(), 1u);
  EXPECT_EQ(r.open_spaces[0].label, kCorridor);
  const cv::Rect inner(ci(4.5), ci(2), ci(14.7), ci(10));
  EXPECT_EQ(cv::countNonZero(r.labels(inner) == kCorridor), inner.area());
  // Without the path nothing is joined.
  const TopologyResult without = buildTopology(hall(kCorridor), kRes, on());
  EXPECT_TRUE(without.open_spaces.empty());
  EXPECT_EQ(cv::countNonZero(without.labels(inner) == kCorridor), ci(9) * ci(10) - ci(0.3) * ci(10));
}

TEST(OpenSpaces, TwoRoomsJoinedByADoorTheRobotCrossedStayTwoNodes) {
  // Room A (x 1..6 m, y 1..6 m), read as room, and room B (x 6.2..11 m), read as corridor, joined by a 0.9 m door in
  // the wall between them (x 6..6.2 m, y 3..3.9 m), its cells read as room. The robot drives from A through the
  // door into B and back.
  cv::Mat labels(ci(7), ci(13), CV_8U, cv::Scalar(places::kNoLabel));
  box(labels, 1, 1, 6, 6, kRoom);
  box(labels, 6.2, 1, 11, 6, kCorridor);
  box(labels, 6, 3, 6.2, 3.9, kRoom);
  const std::vector<cv::Point2d> path = poses({{3, 3.45}, {10, 3.45}, {10, 5}, {7, 5}, {7, 3.45}, {3, 3.45}, {3, 2}});
  const auto spaces = [&](const TopologyOptions& o) {
    const TopologyResult r = buildTopology(labels, kRes, o, nullptr, {0, 0}, path);
    std::multiset<int> out;
    for (const GraphNode& n : r.graph.nodes)
      if (n.label != kDoor) out.insert(n.label);
    EXPECT_TRUE(r.open_spaces.empty());
    return out;
  };
  const std::multiset<int> two{kRoom, kCorridor};
  // The door passage puts a doorway across the door: no straight step from one to the other.
  EXPECT_EQ(spaces(on()), two);
  // Without the door passages and the doorways from geometry the path steps straight from A into B, but through a
  // 0.9 m opening: a constriction (a border shorter than open_space_min_contact).
  TopologyOptions no_passages = on();
  no_passages.door_passages.enabled = false;
  no_passages.doorways.enabled = false;
  EXPECT_EQ(spaces(no_passages), two);
  // With a contact shorter than the door they still keep their labels: the robot went into B (24 m^2, the smaller,
  // whose label would change) and out of it through the same door. Only without that check are they one space.
  no_passages.open_spaces.min_contact = 0.5;
  EXPECT_EQ(spaces(no_passages), two);
  no_passages.open_spaces.min_through = 0;
  EXPECT_EQ(spaces(no_passages), two);  // and B borders A along 0.9 m of its 21.6 m: a room beside A, not a piece
  no_passages.open_spaces.min_shared = 0;
  const TopologyResult joined = buildTopology(labels, kRes, no_passages, nullptr, {0, 0}, path);
  ASSERT_EQ(joined.open_spaces.size(), 1u);
  EXPECT_EQ(joined.open_spaces[0].pieces, 2);
  EXPECT_EQ(joined.open_spaces[0].label, kRoom);
}

TEST(OpenSpaces, ARoomEnteredThroughItsOpenSideAndLeftTheSameWayKeepsItsLabel) {
  // A corridor (x 1..19 m, y 8..10 m) and room D (x 5..11 m, y 3..8 m) open onto it along 3 m (x 6..9 m).
  cv::Mat labels(ci(11), ci(20), CV_8U, cv::Scalar(places::kNoLabel));
  box(labels, 1, 8, 19, 10, kCorridor);
  box(labels, 5, 3, 11, 7.8, kRoom);
  box(labels, 6, 7.8, 9, 8, kRoom);
  const cv::Rect room(ci(5), ci(3), ci(6), ci(4.8));
  // In and out at the same place: the room is no piece of the corridor's space; the room entry is its doorway.
  const TopologyResult same_way = buildTopology(labels, kRes, on(), nullptr, {0, 0},
                                                poses({{2, 9}, {7.5, 9}, {7.5, 5}, {7.5, 9}, {18, 9}}));
  EXPECT_TRUE(same_way.open_spaces.empty());
  EXPECT_EQ(cv::countNonZero(same_way.labels(room) == kRoom) + cv::countNonZero(same_way.labels(room) == kDoor),
            room.area());
  EXPECT_GT(cv::countNonZero(same_way.labels(room) == kRoom), room.area() - ci(1.4) * ci(0.3));
  EXPECT_EQ(same_way.room_entries.size(), 1u);
  // In at x 6.3 m and out at x 8.7 m (2.4 m apart, >= open_space_min_through): the robot went through it, along
  // the corridor's side; but only 3 m of the room's 21.6 m border lie against the corridor (14 % < min_shared 30 %):
  // a room open onto the corridor, not a piece of it. It keeps its label.
  const std::vector<cv::Point2d> through = poses({{2, 9}, {6.3, 9}, {6.3, 5}, {8.7, 5}, {8.7, 9}, {18, 9}});
  const TopologyResult kept = buildTopology(labels, kRes, on(), nullptr, {0, 0}, through);
  EXPECT_TRUE(kept.open_spaces.empty());
  EXPECT_GT(cv::countNonZero(kept.labels(room) == kRoom), room.area() - 2 * ci(1.4) * ci(0.3));
  // With min_shared 0.1 it is a piece of the corridor's space; the corridor (36 m^2) is larger: the room's cells
  // become corridor. A longer min_through keeps it a room again.
  TopologyOptions loose = on();
  loose.open_spaces.min_shared = 0.1;
  const TopologyResult joined = buildTopology(labels, kRes, loose, nullptr, {0, 0}, through);
  ASSERT_EQ(joined.open_spaces.size(), 1u);
  EXPECT_EQ(joined.open_spaces[0].label, kCorridor);
  EXPECT_EQ(cv::countNonZero(joined.labels(room) == kCorridor), room.area());
  loose.open_spaces.min_through = 3;
  EXPECT_TRUE(buildTopology(labels, kRes, loose, nullptr, {0, 0}, through).open_spaces.empty());
}
