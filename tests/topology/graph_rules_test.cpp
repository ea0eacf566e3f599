// The graph a person can read (issue 15, item 4): graph rules G1 / G2 (graph_rules.h), anchors and edge routes
// (edge_route.h) on small synthetic plans.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "gridtopo/places/labelling.h"
#include "gridtopo/topology/edge_route.h"
#include "gridtopo/topology/graph.h"
#include "gridtopo/topology/graph_rules.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/topology/segmentation.h"

using namespace gridtopo;
using namespace gridtopo::topology;

namespace {
constexpr double kRes = 0.05;
constexpr unsigned char R = 0, C = 1, D = 2, N = places::kNoLabel;

// Two rooms above a corridor (walls 10 cells): the left room opens through two doors (a double door), the right
// room through one; a 10 x 20 cell room patch (0.5 m^2) sticks to the corridor, another lies alone.
cv::Mat twoRoomsOverACorridor() {
  cv::Mat l(160, 400, CV_8U, cv::Scalar(N));
  l(cv::Rect(0, 0, 100, 100)).setTo(R);
  l(cv::Rect(110, 0, 90, 100)).setTo(R);
  l(cv::Rect(0, 110, 200, 40)).setTo(C);
  l(cv::Rect(20, 100, 15, 10)).setTo(D);
  l(cv::Rect(60, 100, 15, 10)).setTo(D);
  l(cv::Rect(150, 100, 15, 10)).setTo(D);
  l(cv::Rect(200, 120, 20, 10)).setTo(R);  // tiny, touches the corridor's end
  l(cv::Rect(300, 0, 10, 20)).setTo(R);    // tiny, alone
  return l;
}

int count(const RegionMap& rm, int label) {
  int n = 0;
  for (const auto& r : rm.regions) n += r.label == label;
  return n;
}

// Every straight piece of the edge's path lies on cells of its two regions, and it runs anchor to anchor.
void expectRouteInside(const TopologicalGraph& g, const RegionMap& rm, const GraphEdge& e) {
  ASSERT_GE(e.path_px.size(), 2u) << e.a << "-" << e.b;
  EXPECT_EQ(e.path_px.front(), g.node(e.a)->anchor_px);
  EXPECT_EQ(e.path_px.back(), g.node(e.b)->anchor_px);
  for (std::size_t i = 1; i < e.path_px.size(); ++i) {
    cv::LineIterator it(rm.ids, e.path_px[i - 1], e.path_px[i], 8);
    for (int k = 0; k < it.count; ++k, ++it) {
      const int id = rm.ids.at<int>(it.pos());
      ASSERT_TRUE(id == e.a || id == e.b) << "edge " << e.a << "-" << e.b << " crosses cell " << it.pos() << " (" << id << ")";
    }
  }
}
}  // namespace

TEST(GraphRules, DoorwaysJoiningTheSameTwoRegionsBecomeOneNode) {
  const cv::Mat l = twoRoomsOverACorridor();
  GraphRuleOptions off;
  off.merge_doorways = false;
  off.min_node_area = 0;
  const RegionMap raw = applyGraphRules(extractRegions(l, kRes), kRes, off);
  EXPECT_EQ(count(raw, D), 3);
  const RegionMap rm = applyGraphRules(extractRegions(l, kRes), kRes, {});
  ASSERT_EQ(count(rm, D), 2);  // the double door is one node, the right room's door another
  const TopologicalGraph g = buildGraph(rm, kRes);
  int double_door = 0;
  for (const auto& n : g.nodes)
    if (n.label == D && n.cells == 2 * 150) double_door = n.id;
  ASSERT_NE(double_door, 0);
  // Its anchor is a cell of one of its two parts.
  EXPECT_EQ(rm.ids.at<int>(g.node(double_door)->anchor_px), double_door);
  // room - door - corridor twice, no other edge.
  EXPECT_EQ(g.edges.size(), 4u);
  for (const auto& e : g.edges) {
    EXPECT_TRUE(e.via_doorway);
    expectRouteInside(g, rm, e);
  }
}

TEST(GraphRules, TinyRegionsAreAbsorbedOrRemoved) {
  const cv::Mat l = twoRoomsOverACorridor();
  GraphRuleOptions off;
  off.min_node_area = 0;
  const RegionMap raw = applyGraphRules(extractRegions(l, kRes), kRes, off);
  EXPECT_EQ(count(raw, R), 4);
  const RegionMap rm = applyGraphRules(extractRegions(l, kRes), kRes, {});  // 1 m^2
  EXPECT_EQ(count(rm, R), 2);
  // The patch at the corridor's end joined the corridor (its only neighbour); the lone one left the graph.
  const int corridor = rm.ids.at<int>(130, 100);
  EXPECT_EQ(rm.region(corridor).label, C);
  EXPECT_EQ(rm.region(corridor).cells, 200 * 40 + 200);
  EXPECT_EQ(rm.ids.at<int>(125, 210), corridor);
  EXPECT_EQ(rm.ids.at<int>(10, 305), 0);
  // The labels the rules started from are untouched (graphRegions takes them by const reference) and the chain is
  // the same as the steps one by one.
  const RegionMap regions = extractRegions(l, kRes);
  const RegionMap chained = graphRegions(regions, roomSegmentation(regions), kRes, CorridorSplitOptions{}, GraphRuleOptions{});
  EXPECT_EQ(cv::countNonZero(chained.ids != rm.ids), 0);
}

// Two 5 x 5 m rooms side by side above a corridor, each with its own door, joined through a 1 m gap in the wall
// between them that the classifier labelled room (a missed door): one 8-connected room region.
cv::Mat twoRoomsJoinedThroughAMissedDoor() {
  cv::Mat l(160, 210, CV_8U, cv::Scalar(N));
  l(cv::Rect(0, 0, 100, 100)).setTo(R);
  l(cv::Rect(110, 0, 100, 100)).setTo(R);
  l(cv::Rect(100, 40, 10, 20)).setTo(R);  // the missed door
  l(cv::Rect(0, 110, 210, 40)).setTo(C);
  l(cv::Rect(40, 100, 20, 10)).setTo(D);
  l(cv::Rect(150, 100, 20, 10)).setTo(D);
  return l;
}

TEST(GraphRules, RoomsFollowTheSegmentation) {
  const cv::Mat l = twoRoomsJoinedThroughAMissedDoor();
  const RegionMap regions = extractRegions(l, kRes);
  ASSERT_EQ(count(regions, R), 1);
  TopologyOptions o;  // S1 splits at necks narrower than 1.3 m: the 1 m gap
  const cv::Mat seg = segmentRooms(regions, kRes, o);
  ASSERT_NE(seg.at<int>(50, 50), seg.at<int>(50, 160));

  // G3 off: one room node wired to both doors.
  GraphRuleOptions off;
  off.rooms_by_segment = false;
  EXPECT_EQ(count(graphRegions(regions, seg, kRes, o.corridor_split, off), R), 1);

  // G3 on: one room node per segment, each through its own door to the corridor, and the two joined across the gap.
  const RegionMap rm = graphRegions(regions, seg, kRes, o.corridor_split, o.graph_rules);
  ASSERT_EQ(count(rm, R), 2);
  const int left = rm.ids.at<int>(50, 50), right = rm.ids.at<int>(50, 160);
  ASSERT_NE(left, right);
  EXPECT_EQ(rm.region(left).label, R);
  EXPECT_EQ(rm.region(right).label, R);
  // Every cell of the input room is in one of the two, split at the gap (columns 100..109).
  EXPECT_EQ(rm.region(left).cells + rm.region(right).cells, 100 * 100 * 2 + 10 * 20);
  EXPECT_EQ(rm.ids.at<int>(50, 95), left);
  EXPECT_EQ(rm.ids.at<int>(50, 115), right);
  const TopologicalGraph g = buildGraph(rm, kRes);
  const auto joined = [&](int a, int b) {
    for (const auto& e : g.edges)
      if ((e.a == a && e.b == b) || (e.a == b && e.b == a)) return true;
    return false;
  };
  EXPECT_TRUE(joined(left, right));
  const int door_left = rm.ids.at<int>(105, 50), door_right = rm.ids.at<int>(105, 160);
  EXPECT_TRUE(joined(left, door_left));
  EXPECT_TRUE(joined(right, door_right));
  EXPECT_FALSE(joined(left, door_right));
  EXPECT_FALSE(joined(right, door_left));
  // The same chain from the labels alone.
  EXPECT_EQ(cv::countNonZero(graphRegionsOfLabels(l, kRes, o).ids != rm.ids), 0);
}

TEST(EdgeRoute, AnchorsInsideAndRoutesAroundWalls) {
  // An L-shaped corridor (arms 2 m wide) around a room in its outer corner: the room opens through a door into
  // the horizontal arm far from the corner. The corridor's centroid falls inside the room, and the straight line
  // from the corridor's anchor to the door crosses the wall between them.
  cv::Mat l(200, 200, CV_8U, cv::Scalar(N));
  l(cv::Rect(0, 0, 200, 40)).setTo(C);
  l(cv::Rect(160, 0, 40, 200)).setTo(C);
  l(cv::Rect(0, 50, 150, 150)).setTo(R);
  l(cv::Rect(20, 40, 20, 10)).setTo(D);
  const RegionMap rm = applyGraphRules(extractRegions(l, kRes), kRes, {});
  const TopologicalGraph g = buildGraph(rm, kRes);
  ASSERT_EQ(g.nodes.size(), 3u);
  const GraphNode* corridor = nullptr;
  for (const auto& n : g.nodes)
    if (n.label == C) corridor = &n;
  ASSERT_NE(corridor, nullptr);
  EXPECT_FALSE(corridor->centroid_inside);
  EXPECT_EQ(rm.ids.at<int>(corridor->anchor_px), corridor->id);
  // At least half as deep as the deepest corridor cell (20 cells from the walls): 10 cells from every non-corridor cell.
  for (int y = corridor->anchor_px.y - 9; y <= corridor->anchor_px.y + 9; ++y)
    for (int x = corridor->anchor_px.x - 9; x <= corridor->anchor_px.x + 9; ++x)
      if (std::hypot(x - corridor->anchor_px.x, y - corridor->anchor_px.y) < 9.5) {
        EXPECT_EQ(rm.ids.at<int>(y, x), corridor->id);
      }
  ASSERT_EQ(g.edges.size(), 2u);
  for (const auto& e : g.edges) expectRouteInside(g, rm, e);
  const GraphNode* door = nullptr;
  for (const auto& n : g.nodes)
    if (n.label == D) door = &n;
  ASSERT_NE(door, nullptr);
  // The straight corridor-anchor -> door-anchor line would cross the wall: the route must bend.
  bool straight_crosses = false;
  cv::LineIterator it(rm.ids, corridor->anchor_px, door->anchor_px, 8);
  for (int k = 0; k < it.count; ++k, ++it) straight_crosses |= rm.ids.at<int>(it.pos()) == 0;
  EXPECT_TRUE(straight_crosses);
  for (const auto& e : g.edges)
    if (e.a == corridor->id || e.b == corridor->id) {
      EXPECT_GE(e.path_px.size(), 3u);
    }
}
