#include <gtest/gtest.h>

#include "common/scratch.h"

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <set>

#include "gridtopo/core/error.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/eval/evaluation.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/mrpt_graph.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/topology/segmentation.h"

using namespace gridtopo;
using namespace gridtopo::topology;
using namespace gridtopo::eval;
namespace fs = std::filesystem;

namespace {
constexpr unsigned char R = 0, C = 1, D = 2, N = places::kNoLabel;
// A floor plan at 0.05 m: a corridor 20 x 2 m, three 4 x 4 m rooms above it, each joined by a 1 x 0.4 m door.
cv::Mat floorPlan() {
  cv::Mat l(140, 420, CV_8U, cv::Scalar(N));
  l(cv::Rect(10, 100, 400, 40)).setTo(C);
  for (int i = 0; i < 3; ++i) {
    l(cv::Rect(20 + 130 * i, 10, 80, 80)).setTo(R);
    l(cv::Rect(50 + 130 * i, 90, 20, 10)).setTo(D);
  }
  return l;
}
}  // namespace

TEST(Regions, FloorPlanRegionsAndGraph) {
  const cv::Mat l = floorPlan();
  const RegionMap rm = extractRegions(l, 0.05);
  ASSERT_EQ(rm.regions.size(), 7u);
  int rooms = 0, doors = 0;
  for (const auto& r : rm.regions) {
    rooms += r.label == R, doors += r.label == D;
    if (r.label == R) {
      EXPECT_NEAR(r.area_m2, 16.0, 1e-9);
    }
  }
  EXPECT_EQ(rooms, 3);
  EXPECT_EQ(doors, 3);
  const TopologicalGraph g = buildGraph(rm, 0.05);
  ASSERT_EQ(g.edges.size(), 6u);  // room - door - corridor, three times; rooms never touch the corridor
  for (const auto& e : g.edges) EXPECT_TRUE(e.via_doorway);
  EXPECT_EQ(g.connectedComponents(), 1);
  const GraphNode* room = nullptr;
  for (const auto& n : g.nodes)
    if (n.label == R && n.bbox_px.x == 20) room = &n;
  ASSERT_NE(room, nullptr);
  EXPECT_NEAR(room->centroid_px.x, 59.5, 1e-9);
  EXPECT_NEAR(room->centroid_m.x, 3.0, 1e-9);
  EXPECT_NEAR(room->centroid_m.y, (140 - 49.5 - 0.5) * 0.05, 1e-9);
  EXPECT_EQ(room->cells, 6400);
}

// The edge routes work on the box of the regions' cells: the same plan in a corner of a large empty map gives the
// same routes, moved by the plan's offset (an irregular plan, so that routes bend and ties are broken).
TEST(Regions, EdgeRoutesDoNotDependOnTheEmptyMapAroundTheRegions) {
  cv::Mat l = floorPlan();
  cv::circle(l, {300, 60}, 25, cv::Scalar(C), cv::FILLED);  // a hall bulging off the third room
  l(cv::Rect(150, 100, 30, 8)).setTo(N);                      // a pillar row in the corridor
  const TopologicalGraph tight = buildGraph(extractRegions(l, 0.05), 0.05);
  cv::Mat big(900, 1300, CV_8U, cv::Scalar(N));
  const cv::Point off(777, 611);
  l.copyTo(big(cv::Rect(off, l.size())));
  const TopologicalGraph wide = buildGraph(extractRegions(big, 0.05), 0.05);
  ASSERT_EQ(wide.edges.size(), tight.edges.size());
  ASSERT_GE(tight.edges.size(), 6u);
  for (std::size_t i = 0; i < tight.edges.size(); ++i) {
    ASSERT_EQ(wide.edges[i].path_px.size(), tight.edges[i].path_px.size()) << i;
    EXPECT_GE(tight.edges[i].path_px.size(), 2u);
    for (std::size_t k = 0; k < tight.edges[i].path_px.size(); ++k)
      EXPECT_EQ(wide.edges[i].path_px[k], tight.edges[i].path_px[k] + off) << i << " " << k;
  }
  for (std::size_t i = 0; i < tight.nodes.size(); ++i) EXPECT_EQ(wide.nodes[i].anchor_px, tight.nodes[i].anchor_px + off);
}

TEST(Segmentation, DoorsSplitRoomsAndJoinTheirNeighbours) {
  const cv::Mat l = floorPlan();
  const cv::Mat seg = roomSegmentation(extractRegions(l, 0.05));
  EXPECT_EQ(segmentCount(seg), 4);
  EXPECT_EQ(cv::countNonZero(seg), cv::countNonZero(l != N));
  // Door cells next to the room belong to the room, next to the corridor to the corridor.
  EXPECT_EQ(seg.at<int>(91, 60), seg.at<int>(50, 60));
  EXPECT_EQ(seg.at<int>(99, 60), seg.at<int>(120, 60));
  // Scored against itself: perfect.
  const auto s = scoreSegmentation(seg, seg);
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
  EXPECT_DOUBLE_EQ(s.recall, 1.0);
}

TEST(Segmentation, S0MergesAnOpenRoomCorridorContactButNotADoorWidth) {
  // A room label wrongly covering the end of the corridor: the "room" touches the corridor along its 2 m
  // width, without a doorway. A second room hangs off the corridor through a missed door (1 m opening).
  cv::Mat l(140, 420, CV_8U, cv::Scalar(N));
  l(cv::Rect(10, 100, 400, 40)).setTo(C);
  l(cv::Rect(330, 100, 80, 40)).setTo(R);   // the corridor's last 4 m labelled room: contact 2 m
  l(cv::Rect(20, 10, 80, 80)).setTo(R);     // a 4 x 4 m room ...
  l(cv::Rect(50, 90, 20, 10)).setTo(R);     // ... joined to the corridor by a 1 m opening labelled room
  const RegionMap rm = extractRegions(l, 0.05);
  EXPECT_EQ(segmentCount(roomSegmentation(rm)), 3);
  const cv::Mat seg = roomSegmentation(rm, 1.5, 0.05);
  EXPECT_EQ(segmentCount(seg), 2);
  EXPECT_EQ(seg.at<int>(120, 370), seg.at<int>(120, 100));  // merged: one place
  EXPECT_NE(seg.at<int>(50, 60), seg.at<int>(120, 100));    // the room behind the 1 m opening stays apart
  EXPECT_EQ(segmentCount(roomSegmentation(rm, 2.5, 0.05)), 3);  // contact 2 m < 2.5 m: no merge
}

TEST(Segmentation, S1SplitsTwoRoomsJoinedThroughANarrowOpening) {
  // Two 4 x 4 m rooms side by side, joined by a 0.9 m opening in a 0.2 m wall, labelled one room segment.
  cv::Mat seg(100, 200, CV_32S, cv::Scalar(0));
  seg(cv::Rect(10, 10, 80, 80)).setTo(1);
  seg(cv::Rect(94, 10, 80, 80)).setTo(1);
  seg(cv::Rect(90, 40, 4, 18)).setTo(1);  // the opening: 0.9 m wide, 0.2 m deep
  seg(cv::Rect(180, 10, 10, 10)).setTo(2);
  SegmentationRules o;
  o.neck_width = 1.2;
  o.min_part_area = 4.0;
  const cv::Mat out = splitAtNecks(seg, 0.05, o);
  EXPECT_EQ(segmentCount(out), 3);
  EXPECT_NE(out.at<int>(50, 30), out.at<int>(50, 150));
  EXPECT_EQ(out.at<int>(50, 30), 1);
  EXPECT_EQ(out.at<int>(15, 185), 2);                               // the small segment is untouched
  EXPECT_EQ(cv::countNonZero(out), cv::countNonZero(seg));          // no cell lost
  // The split runs through the opening: its left half goes left, its right half right.
  EXPECT_EQ(out.at<int>(50, 90), out.at<int>(50, 30));
  EXPECT_EQ(out.at<int>(50, 93), out.at<int>(50, 150));
  // A wider opening (1.6 m) is a passage, not a door: no split at neck width 1.2 m.
  seg(cv::Rect(90, 30, 4, 32)).setTo(1);
  EXPECT_EQ(segmentCount(splitAtNecks(seg, 0.05, o)), 2);
  // Parts smaller than min_part_area do not split.
  o.neck_width = 1.2, o.min_part_area = 20.0;
  seg(cv::Rect(90, 30, 4, 32)).setTo(0);
  seg(cv::Rect(90, 40, 4, 18)).setTo(1);
  EXPECT_EQ(segmentCount(splitAtNecks(seg, 0.05, o)), 2);
  // Off at neck width 0.
  o.neck_width = 0;
  EXPECT_EQ(cv::norm(splitAtNecks(seg, 0.05, o), seg, cv::NORM_INF), 0.0);
}

// S1 numbers the parts of a split segment in the order of their first 2 x 2 block (row-major), as
// cv::connectedComponents numbers components: the first keeps the segment's id, the others take new ids after the
// last segment, in that order.
TEST(Segmentation, S1NumbersThePartsInTheOrderOfTheirFirstBlock) {
  // Three 4 x 4 m rooms of segment 1 joined by 0.9 m openings: top right, then middle left, then bottom right
  // (reading order of their top-left corners); segment 2 elsewhere.
  cv::Mat seg(300, 260, CV_32S, cv::Scalar(0));
  seg(cv::Rect(150, 10, 80, 80)).setTo(1);   // A
  seg(cv::Rect(60, 101, 80, 80)).setTo(1);   // B (starts on an odd row)
  seg(cv::Rect(150, 193, 80, 80)).setTo(1);  // C
  seg(cv::Rect(150, 90, 18, 11)).setTo(1);   // A-B: a corridor stub 0.9 m wide ...
  seg(cv::Rect(140, 150, 10, 18)).setTo(1);  // B-C
  seg(cv::Rect(150, 150, 18, 43)).setTo(1);
  seg(cv::Rect(10, 10, 10, 10)).setTo(2);
  SegmentationRules o;
  o.neck_width = 1.2;
  o.min_part_area = 4.0;
  const cv::Mat out = splitAtNecks(seg, 0.05, o);
  EXPECT_EQ(segmentCount(out), 4);
  EXPECT_EQ(out.at<int>(50, 190), 1);   // A keeps the id
  EXPECT_EQ(out.at<int>(140, 100), 3);  // B next
  EXPECT_EQ(out.at<int>(240, 190), 4);  // C last
  EXPECT_EQ(out.at<int>(15, 15), 2);
  EXPECT_EQ(cv::countNonZero(out), cv::countNonZero(seg));
  // The same split whatever the crop's offset in the map (the blocks are the crop's).
  cv::Mat shifted(seg.rows + 3, seg.cols + 5, CV_32S, cv::Scalar(0));
  seg.copyTo(shifted(cv::Rect(5, 3, seg.cols, seg.rows)));
  const cv::Mat out_shifted = splitAtNecks(shifted, 0.05, o);
  EXPECT_EQ(cv::norm(out_shifted(cv::Rect(5, 3, seg.cols, seg.rows)), out, cv::NORM_INF), 0.0);
}

// In 16 bits (gridtopo-topology's runs on the box of a large map) the segmentation and its neck split give the
// same ids as in 32 bits.
TEST(Segmentation, SixteenBitsGiveTheSameIds) {
  // Two rooms joined by a narrow opening (split by S1), a corridor, a door between room and corridor.
  cv::Mat labels(100, 200, CV_8U, cv::Scalar(places::kNoLabel));
  labels(cv::Rect(10, 10, 80, 80)).setTo(0);
  labels(cv::Rect(94, 10, 80, 80)).setTo(0);
  labels(cv::Rect(90, 40, 4, 18)).setTo(0);
  labels(cv::Rect(10, 92, 180, 6)).setTo(1);
  labels(cv::Rect(30, 90, 10, 2)).setTo(2);
  const RegionMap rm = extractRegions(labels, 0.05);
  TopologyOptions o;
  const cv::Mat wide = segmentRooms(rm, 0.05, o), narrow = segmentRooms(rm, 0.05, o, true);
  ASSERT_EQ(wide.type(), CV_32S);
  ASSERT_EQ(narrow.type(), CV_16U);
  EXPECT_EQ(segmentCount(wide), 3);  // the rooms split at the opening, the corridor with its door
  cv::Mat back;
  narrow.convertTo(back, CV_32S);
  EXPECT_EQ(cv::norm(back, wide, cv::NORM_INF), 0.0);
  o.segmentation = "doorways";
  segmentRooms(rm, 0.05, o, true).convertTo(back, CV_32S);
  EXPECT_EQ(cv::norm(back, segmentRooms(rm, 0.05, o), cv::NORM_INF), 0.0);
}

TEST(Segmentation, S1FillsFurnitureEnclosedByTheSegment) {
  // The two rooms of the test above, furnished: a 0.2 x 0.2 m chair every metre. The 0.6 m band around every
  // chair eats each room's core, so without filling no part is large enough and the missed door is not split.
  cv::Mat seg(100, 200, CV_32S, cv::Scalar(0));
  seg(cv::Rect(10, 10, 80, 80)).setTo(1);
  seg(cv::Rect(94, 10, 80, 80)).setTo(1);
  seg(cv::Rect(90, 40, 4, 18)).setTo(1);  // the opening: 0.9 m wide
  for (int y = 18; y < 90; y += 20)
    for (int x = 18; x < 174; x += 20)
      if (x < 84 || x > 100) seg(cv::Rect(x, y, 4, 4)).setTo(0);
  seg(cv::Rect(140, 50, 6, 6)).setTo(2);  // a small segment inside the right room: not an obstacle
  SegmentationRules o;
  o.neck_width = 1.2;
  o.min_part_area = 4.0;
  o.fill_obstacle_area = 0;  // round 2: no filling
  const cv::Mat plain = splitAtNecks(seg, 0.05, o);
  EXPECT_EQ(segmentCount(plain), 2);
  EXPECT_EQ(plain.at<int>(50, 30), plain.at<int>(30, 150));
  o.fill_obstacle_area = 0.1;  // chairs are 0.04 m^2
  const cv::Mat out = splitAtNecks(seg, 0.05, o);
  EXPECT_EQ(segmentCount(out), 3);
  EXPECT_NE(out.at<int>(50, 30), out.at<int>(30, 150));
  EXPECT_EQ(out.at<int>(50, 90), out.at<int>(50, 30));   // split through the opening
  EXPECT_EQ(out.at<int>(50, 93), out.at<int>(30, 150));
  EXPECT_EQ(out.at<int>(52, 142), 2);                    // the small segment keeps its id
  EXPECT_EQ(cv::countNonZero(out), cv::countNonZero(seg));  // chairs stay non-segment cells
  EXPECT_EQ(out.at<int>(19, 19), 0);
  // Obstacles larger than the fill area are walls: no split again.
  o.fill_obstacle_area = 0.03;
  EXPECT_EQ(segmentCount(splitAtNecks(seg, 0.05, o)), 2);
}

TEST(Segmentation, SegmentVoteGivesEachSegmentOneLabel) {
  // The floor plan's left room is 60 % room, 40 % corridor (a confusion inside the room); a doorway keeps its label.
  cv::Mat l = floorPlan();
  l(cv::Rect(20, 10, 80, 32)).setTo(C);
  TopologyResult plain = buildTopology(l, 0.05, TopologyOptions{});
  TopologyOptions o;
  o.seg_rules.segment_vote = true;
  o.seg_rules.merge_contact = 1.0;  // the corridor-labelled strip touches the room along 4 m: one segment
  const TopologyResult voted = buildTopology(l, 0.05, o);
  EXPECT_EQ(voted.labels.at<unsigned char>(20, 60), R);  // the strip became room
  EXPECT_EQ(voted.labels_corrected.at<unsigned char>(20, 60), C);
  EXPECT_EQ(voted.labels.at<unsigned char>(95, 60), D);  // the door stays a door
  EXPECT_EQ(voted.labels.at<unsigned char>(120, 200), C);  // the corridor stays a corridor
  EXPECT_EQ(plain.labels.at<unsigned char>(20, 60), C);
  // Regions and graph follow the voted labels: three rooms, three doors, one corridor.
  EXPECT_EQ(voted.regions.regions.size(), 7u);
  EXPECT_EQ(voted.graph.nodes.size(), 7u);
  // Directly: a segment with more corridor than room cells becomes corridor.
  cv::Mat lab(l.size(), CV_8U, cv::Scalar(N));
  lab(cv::Rect(0, 0, 10, 10)).setTo(R);
  lab(cv::Rect(10, 0, 11, 10)).setTo(C);
  cv::Mat seg(l.size(), CV_32S, cv::Scalar(0));
  seg(cv::Rect(0, 0, 21, 10)).setTo(4);
  const cv::Mat v = voteLabelsInSegments(lab, seg);
  EXPECT_EQ(cv::countNonZero(v == C), 210);
  EXPECT_EQ(cv::countNonZero(v == R), 0);
}

TEST(Correction, RulesOnTheFloorPlan) {
  cv::Mat l = floorPlan();
  l(cv::Rect(30, 20, 6, 6)).setTo(C);        // R1: a 0.09 m^2 corridor speck inside room 1
  l(cv::Rect(300, 40, 10, 10)).setTo(D);     // R2: a doorway blob inside room 3 joins nothing
  l(cv::Rect(200, 5, 3, 3)).setTo(R);        // R0: an isolated 9-cell free patch
  CorrectionOptions o;
  CorrectionStats st;
  const cv::Mat c = correctRegions(l, 0.05, o, &st);
  EXPECT_EQ(st.patches_removed, 1);
  EXPECT_GE(st.small_merged, 1);
  EXPECT_EQ(st.doorways_not_separating, 1);
  EXPECT_EQ(c.at<unsigned char>(22, 32), R);
  EXPECT_EQ(c.at<unsigned char>(45, 305), R);
  EXPECT_EQ(c.at<unsigned char>(6, 201), N);
  EXPECT_EQ(cv::countNonZero(c != floorPlan()), 0);  // exactly the original plan again
  o.enabled = false;
  EXPECT_EQ(cv::countNonZero(correctRegions(l, 0.05, o) != l), 0);
}

TEST(Export, FilesParseBack) {
  const auto rm = extractRegions(floorPlan(), 0.05);
  const auto g = buildGraph(rm, 0.05);
  const fs::path dir = gridtopo::test::scratchPath("topology_export_test");
  fs::create_directories(dir);
  std::ofstream(dir / "t.json") << toJson(g);
  const auto back = graphFromJson((dir / "t.json").string());
  ASSERT_EQ(back.nodes.size(), g.nodes.size());
  ASSERT_EQ(back.edges.size(), g.edges.size());
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    EXPECT_EQ(back.nodes[i].id, g.nodes[i].id);
    EXPECT_EQ(back.nodes[i].label, g.nodes[i].label);
    EXPECT_NEAR(back.nodes[i].area_m2, g.nodes[i].area_m2, 1e-9);
    EXPECT_NEAR(back.nodes[i].centroid_m.y, g.nodes[i].centroid_m.y, 1e-9);
    EXPECT_EQ(back.nodes[i].bbox_px, g.nodes[i].bbox_px);
    EXPECT_EQ(back.nodes[i].anchor_px, g.nodes[i].anchor_px);
  }
  for (std::size_t i = 0; i < g.edges.size(); ++i) {
    EXPECT_EQ(back.edges[i].a, g.edges[i].a);
    EXPECT_EQ(back.edges[i].b, g.edges[i].b);
    EXPECT_EQ(back.edges[i].via_doorway, g.edges[i].via_doorway);
    EXPECT_GE(g.edges[i].path_px.size(), 2u);
    EXPECT_EQ(back.edges[i].path_px, g.edges[i].path_px);  // the routed path survives the round trip
  }
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    EXPECT_NEAR(back.nodes[i].anchor_m.x, g.nodes[i].anchor_m.x, 1e-9);
    EXPECT_NEAR(back.nodes[i].anchor_m.y, g.nodes[i].anchor_m.y, 1e-9);
  }
  // GraphML: one <node> per node, one <edge> per edge, every edge endpoint declared.
  const std::string gml = toGraphML(g);
  std::set<std::string> ids;
  const std::regex node_re("<node id=\"(n[0-9]+)\">"), edge_re("<edge source=\"(n[0-9]+)\" target=\"(n[0-9]+)\">");
  for (auto it = std::sregex_iterator(gml.begin(), gml.end(), node_re); it != std::sregex_iterator(); ++it)
    ids.insert((*it)[1]);
  EXPECT_EQ(ids.size(), g.nodes.size());
  std::size_t edges = 0;
  for (auto it = std::sregex_iterator(gml.begin(), gml.end(), edge_re); it != std::sregex_iterator(); ++it, ++edges) {
    EXPECT_TRUE(ids.count((*it)[1]));
    EXPECT_TRUE(ids.count((*it)[2]));
  }
  EXPECT_EQ(edges, g.edges.size());
  EXPECT_NE(gml.find("</graphml>"), std::string::npos);
  const std::string dot = toDot(g);
  std::size_t dash = 0;
  for (std::size_t p = 0; (p = dot.find(" -- ", p)) != std::string::npos; ++p) ++dash;
  EXPECT_EQ(dash, g.edges.size());
  std::ofstream(dir / "bad.json") << "{\"format\": \"other\"}";
  EXPECT_THROW(graphFromJson((dir / "bad.json").string()), InputError);
  // Overlay and 16-bit segmentation image.
  places::OccupancyImage occ;
  occ.resolution = 0.05;
  occ.cells = cv::Mat(floorPlan().size(), CV_8U, cv::Scalar(places::kOccupied));
  occ.cells.setTo(places::kFree, floorPlan() != N);
  const cv::Mat ov = renderOverlay(occ, floorPlan(), rm, g, 2);
  EXPECT_EQ(ov.size(), cv::Size(840, 280));
  const cv::Mat s16 = segmentationImage16(roomSegmentation(rm));
  EXPECT_EQ(s16.type(), CV_16U);
  EXPECT_TRUE(cv::imwrite((dir / "seg.png").string(), s16));
  const cv::Mat s16b = cv::imread((dir / "seg.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(cv::norm(s16, s16b, cv::NORM_INF), 0.0);
}

TEST(Evaluation, SegmentationScoreDefinition) {
  cv::Mat gt(10, 20, CV_32S, cv::Scalar(0));
  gt(cv::Rect(0, 0, 10, 10)).setTo(1);
  gt(cv::Rect(10, 0, 10, 10)).setTo(2);
  cv::Mat seg(10, 20, CV_32S, cv::Scalar(1));  // one segment over both rooms
  auto s = scoreSegmentation(seg, gt);
  EXPECT_DOUBLE_EQ(s.recall, 1.0);
  EXPECT_DOUBLE_EQ(s.precision, 0.5);
  seg(cv::Rect(0, 0, 5, 10)).setTo(2);  // room 1 split in halves, the second half merged with room 2
  s = scoreSegmentation(seg, gt);
  EXPECT_DOUBLE_EQ(s.recall, (0.5 + 1.0) / 2);
  EXPECT_DOUBLE_EQ(s.precision, (1.0 + 100.0 / 150.0) / 2);
  EXPECT_NEAR(s.precision_weighted, (50.0 + 100.0) / 200.0, 1e-12);
}

TEST(Evaluation, ConfusionMatrix) {
  cv::Mat truth(1, 4, CV_8U), pred(1, 4, CV_8U);
  truth.at<unsigned char>(0) = 77, truth.at<unsigned char>(1) = 115, truth.at<unsigned char>(2) = 179, truth.at<unsigned char>(3) = 77;
  pred.at<unsigned char>(0) = R, pred.at<unsigned char>(1) = C, pred.at<unsigned char>(2) = R, pred.at<unsigned char>(3) = N;
  ConfusionMatrix m;
  m.add(truth, pred);
  EXPECT_EQ(m.total(), 3);
  EXPECT_EQ(m.unpredicted, 1);
  EXPECT_DOUBLE_EQ(m.accuracy(), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(m.precision(0), 0.5);
  EXPECT_DOUBLE_EQ(m.recall(2), 0.0);
}

TEST(Evaluation, GroundTruthRoomsOfLabIntel) {
  const cv::Mat gt = cv::imread(std::string(GRIDTOPO_DATA_DIR) + "/places/groundtruth/lab_intel_gt_segmentation.png",
                                cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(gt.empty());
  EXPECT_EQ(segmentCount(groundTruthRooms(gt)), 26);
}

TEST(Export, MrptPoseGraphRoundTrip) {
  const auto g = buildGraph(extractRegions(floorPlan(), 0.05), 0.05);
  const auto pg = toMrptPoseGraph(g);
  EXPECT_EQ(pg.nodes.size(), g.nodes.size());
  EXPECT_EQ(pg.edgeCount(), g.edges.size());
  const fs::path p = gridtopo::test::scratchPath("topology_posegraph.graph");
  pg.saveToTextFile(p.string());
  mrpt::graphs::CNetworkOfPoses2D back;
  back.loadFromTextFile(p.string());
  ASSERT_EQ(back.nodes.size(), g.nodes.size());
  const auto& n0 = g.nodes.front();
  EXPECT_NEAR(back.nodes.at(static_cast<mrpt::graphs::TNodeID>(n0.id)).x(), n0.anchor_m.x, 1e-6);
  EXPECT_EQ(back.edgeCount(), g.edges.size());
}
