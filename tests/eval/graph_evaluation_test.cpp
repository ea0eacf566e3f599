// Graph quality against a labelled plan (graph_evaluation.h): on a synthetic plan where the answer is known, the
// correct graph scores 100 % and closes the loop; a merged room, a missing doorway and a broken loop cost exactly
// what the definitions say.
#include <gtest/gtest.h>

#include "gridtopo/places/labelling.h"
#include "gridtopo/topology/graph.h"
#include "gridtopo/eval/graph_evaluation.h"
#include "gridtopo/topology/graph_rules.h"
#include "gridtopo/topology/pipeline.h"

using namespace gridtopo;
using namespace gridtopo::topology;
using namespace gridtopo::eval;

namespace {
constexpr double kRes = 0.05;
constexpr unsigned char R = 0, C = 1, D = 2, N = places::kNoLabel;

// 400 x 300 cells (20 x 15 m): a corridor ring 2 m wide around a 6 x 4 m block, with a 4 m spur on either side
// (so the corridor has two junctions), two rooms above the ring and one below, each opening through a door.
cv::Mat planLabels() {
  cv::Mat l(300, 400, CV_8U, cv::Scalar(N));
  l(cv::Rect(100, 70, 200, 160)).setTo(C);
  l(cv::Rect(140, 110, 120, 80)).setTo(N);
  l(cv::Rect(20, 135, 80, 30)).setTo(C);
  l(cv::Rect(300, 135, 80, 30)).setTo(C);
  l(cv::Rect(100, 10, 95, 50)).setTo(R);   // plan room 1
  l(cv::Rect(205, 10, 95, 50)).setTo(R);   // plan room 2
  l(cv::Rect(100, 240, 200, 50)).setTo(R); // plan room 3
  l(cv::Rect(140, 60, 16, 10)).setTo(D);
  l(cv::Rect(240, 60, 16, 10)).setTo(D);
  l(cv::Rect(190, 230, 16, 10)).setTo(D);
  return l;
}

struct Plan {
  cv::Mat free, codes, rooms;
};
// The reference: free pixels, codes 77 / 115 / 179, and ground-truth regions (rooms 1-3, the corridor 4) that,
// as in the benchmark's ground truth, leave the doors out.
Plan reference() {
  const cv::Mat l = planLabels();
  Plan p;
  p.free = l != N;
  p.codes = places::labelsToCodes(l);
  p.rooms = cv::Mat(l.size(), CV_32S, cv::Scalar(0));
  p.rooms(cv::Rect(100, 10, 95, 50)).setTo(1);
  p.rooms(cv::Rect(205, 10, 95, 50)).setTo(2);
  p.rooms(cv::Rect(100, 240, 200, 50)).setTo(3);
  p.rooms.setTo(4, l == C);
  return p;
}

ReferenceAlignment identity() {
  ReferenceAlignment a;
  a.map_to_reference = cv::Matx23d(1, 0, 0, 0, 1, 0);
  a.correlation = 1;
  return a;
}

GraphScore score(const cv::Mat& labels) {
  const Plan p = reference();
  TopologyOptions o;
  o.corridor_split.min_branch = 1.0;  // the 4 m spurs are branches
  const RegionMap rm = graphRegionsOfLabels(labels, kRes, o);
  const TopologicalGraph g = buildGraph(rm, kRes);
  const PlanGraph plan = planGraphFromReference(labels != N, p.free, p.codes, p.rooms, identity(), kRes);
  return scoreGraph(g, rm, plan);
}
}  // namespace

TEST(PlanGraph, RegionsKindsOpeningsAndLoopOfTheSyntheticPlan) {
  const Plan p = reference();
  const PlanGraph plan = planGraphFromReference(p.free, p.free, p.codes, p.rooms, identity(), kRes);
  ASSERT_EQ(plan.kind.size(), 4u);
  EXPECT_EQ(plan.kind.at(1), R);
  EXPECT_EQ(plan.kind.at(3), R);
  EXPECT_EQ(plan.kind.at(4), C);
  // Three doors, each joining its room and the corridor.
  ASSERT_EQ(plan.links.size(), 3u);
  for (int r = 1; r <= 3; ++r) {
    ASSERT_TRUE(plan.links.count({r, 4}));
    EXPECT_TRUE(plan.links.at({r, 4}));
  }
  // One loop, its point inside the block.
  ASSERT_EQ(plan.loop_points.size(), 1u);
  EXPECT_TRUE(cv::Rect(140, 110, 120, 80).contains(plan.loop_points[0]));
}

TEST(GraphScore, TheCorrectGraphScoresFull) {
  const GraphScore s = score(planLabels());
  EXPECT_EQ(s.plan_rooms, 3);
  EXPECT_EQ(s.one_room_node, 3);
  EXPECT_EQ(s.attached, 3);
  EXPECT_DOUBLE_EQ(s.attachedFraction(), 1.0);
  EXPECT_EQ(s.plan_loops, 1);
  EXPECT_EQ(s.loops_closed, 1);
  EXPECT_TRUE(s.loopsClosed());
  EXPECT_EQ(s.corridor_cycles, 1);
}

TEST(GraphScore, AMergedRoomCostsBothItsRooms) {
  cv::Mat l = planLabels();
  l(cv::Rect(195, 10, 10, 50)).setTo(R);  // the wall between rooms 1 and 2 is gone: one room node over both
  const GraphScore s = score(l);
  EXPECT_EQ(s.plan_rooms, 3);
  EXPECT_EQ(s.one_room_node, 1);
  EXPECT_EQ(s.attached, 1);
  EXPECT_NEAR(s.attachedFraction(), 1.0 / 3.0, 1e-12);
  EXPECT_TRUE(s.loopsClosed());
}

TEST(GraphScore, AMissingDoorwayCostsItsRoom) {
  cv::Mat l = planLabels();
  l(cv::Rect(190, 230, 16, 10)).setTo(R);  // room 3's door read as room: the room touches the corridor directly
  const GraphScore s = score(l);
  EXPECT_EQ(s.one_room_node, 3);
  EXPECT_EQ(s.attached, 2);
  EXPECT_NEAR(s.attachedFraction(), 2.0 / 3.0, 1e-12);
  ASSERT_EQ(s.rooms.size(), 3u);
  EXPECT_FALSE(s.rooms[2].attached);
  EXPECT_TRUE(s.rooms[2].one_room_node);
}

TEST(GraphScore, ARoomNodeInTheRingBreaksTheLoop) {
  cv::Mat l = planLabels();
  l(cv::Rect(100, 180, 50, 50)).setTo(R);  // the ring's south-west corner read as room (the Intel SW junction)
  const GraphScore s = score(l);
  EXPECT_EQ(s.plan_loops, 1);
  EXPECT_EQ(s.loops_closed, 0);
  EXPECT_FALSE(s.loopsClosed());
  EXPECT_EQ(s.attached, 3);  // the rooms are unaffected
}

TEST(GraphScore, OnlyACycleAroundTheLoopPointCounts) {
  // Three corridor nodes in a triangle around (50, 50), joined by straight edges (no routed paths), and a doorway
  // node between two of them that adds a second, thin cycle.
  TopologicalGraph g;
  g.rows = g.cols = 200;
  const cv::Point at[4] = {{20, 20}, {90, 30}, {40, 90}, {60, 15}};
  for (int i = 0; i < 4; ++i) {
    GraphNode n;
    n.id = i + 1, n.label = i < 3 ? C : D, n.anchor_px = at[i];
    g.nodes.push_back(n);
  }
  for (const auto& [a, b] : std::vector<std::pair<int, int>>{{1, 2}, {2, 3}, {1, 3}, {1, 4}, {2, 4}}) {
    GraphEdge e;
    e.a = a, e.b = b;
    g.edges.push_back(e);
  }
  RegionMap rm;
  rm.ids = cv::Mat(200, 200, CV_32S, cv::Scalar(0));
  PlanGraph plan;
  plan.regions = cv::Mat(200, 200, CV_32S, cv::Scalar(0));
  plan.loop_points = {{50, 50}, {150, 150}, {60, 21}};  // inside the triangle, outside, inside the thin cycle
  const GraphScore s = scoreGraph(g, rm, plan);
  EXPECT_EQ(s.corridor_cycles, 2);
  EXPECT_EQ(s.plan_loops, 3);
  EXPECT_EQ(s.loops_closed, 2);
  EXPECT_FALSE(s.loopsClosed());
  plan.loop_points = {{50, 50}};
  EXPECT_TRUE(scoreGraph(g, rm, plan).loopsClosed());
  g.edges.erase(g.edges.begin() + 1);  // without the edge 2 - 3 no cycle goes round (50, 50)
  EXPECT_FALSE(scoreGraph(g, rm, plan).loopsClosed());
}
