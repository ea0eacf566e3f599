// Door passages (door_passages.h): a building drawn on a 5 cm grid, a corridor (x 1..19 m, y 8..10 m) with room A
// (x 1..6 m) and room B (x 6.2..12 m) above it, each through a 0.9 m door in the corridor's north wall (y 7.8..8 m),
// and room C (x 12.2..19 m) with no door onto the corridor, reached from room B through a 1.3 m opening in the wall
// between them (x 12..12.2 m, y 3..4.3 m): no door to the geometry (wider than doorway_max_width 1.2 m). The
// simulated classifier labels rooms and corridor and no doorway. The robot drives from room A through door A, along
// the corridor, through door B into room B and through the opening into room C.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <map>
#include <set>
#include <string>

#include "gridtopo/core/error.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/door_passages.h"
#include "gridtopo/topology/doorway_geometry.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/pipeline.h"

using namespace gridtopo;
using namespace gridtopo::topology;

namespace {

constexpr double kRes = 0.05;
constexpr unsigned char kRoom = 0, kCorridor = 1, kDoor = 2;

double c(double m) { return m / kRes; }
int ci(double m) { return static_cast<int>(std::lround(m / kRes)); }

struct Building {
  cv::Mat free;    // 255 = free
  cv::Mat labels;  // the simulated classifier's: rooms and corridor, no doorway
};

Building makeBuilding() {
  Building b;
  b.free = cv::Mat::zeros(ci(11), ci(20), CV_8U);
  b.labels = cv::Mat(b.free.size(), CV_8U, cv::Scalar(places::kNoLabel));
  const auto box = [&](double x0, double y0, double x1, double y1, unsigned char label) {
    const cv::Rect r(cv::Point(ci(x0), ci(y0)), cv::Point(ci(x1), ci(y1)));
    b.free(r).setTo(255);
    b.labels(r).setTo(label);
  };
  box(1, 8, 19, 10, kCorridor);
  box(1, 1, 6, 7.8, kRoom);        // A
  box(6.2, 1, 12, 7.8, kRoom);     // B
  box(12.2, 1, 19, 7.8, kRoom);    // C
  box(3, 7.8, 3.9, 8, kRoom);      // door A
  box(9, 7.8, 9.9, 8, kRoom);      // door B
  box(12, 3, 12.2, 4.3, kRoom);    // the opening between B and C
  return b;
}

// A polyline as a trajectory: a pose every 0.1 m.
std::vector<cv::Point2d> poses(const std::vector<cv::Point2d>& corners) {
  std::vector<cv::Point2d> out{corners.front()};
  for (std::size_t i = 1; i < corners.size(); ++i) {
    const cv::Point2d d = corners[i] - corners[i - 1];
    const int n = std::max(1, static_cast<int>(std::ceil(cv::norm(d) / c(0.1))));
    for (int k = 1; k <= n; ++k) out.push_back(corners[i - 1] + d * (double(k) / n));
  }
  return out;
}

// The robot's path in cells: room A, door A, the corridor, door B, room B, the opening, room C.
std::vector<cv::Point2d> drive() {
  return poses({{c(3.45), c(4.0)}, {c(3.45), c(8.9)}, {c(9.45), c(8.9)}, {c(9.45), c(6.0)},
                {c(10.0), c(3.65)}, {c(15.5), c(3.65)}});
}

// Which space a node's anchor lies in.
std::string space(const GraphNode& n) {
  const double x = (n.anchor_px.x + 0.5) * kRes, y = (n.anchor_px.y + 0.5) * kRes;
  if (y >= 8) return "corridor";
  if (y >= 7.8) return x < 6 ? "door A" : "door B";
  if (x < 6) return "A";
  if (x < 12) return "B";
  if (x < 12.2) return "opening";
  return "C";
}

// For every doorway node, the spaces of its neighbours (sorted, joined by '|').
std::multiset<std::string> doorwaysBetween(const TopologicalGraph& g) {
  std::multiset<std::string> out;
  for (const GraphNode& n : g.nodes) {
    if (n.label != kDoor) continue;
    std::set<std::string> sides;
    for (const GraphEdge& e : g.edges)
      if (e.a == n.id || e.b == n.id) sides.insert(space(*g.node(e.a == n.id ? e.b : e.a)));
    std::string s;
    for (const std::string& side : sides) s += (s.empty() ? "" : "|") + side;
    out.insert(s);
  }
  return out;
}

}  // namespace

TEST(DoorPassages, ThePathWentThroughThreeDoorsOfTheirWidths) {
  const Building b = makeBuilding();
  const std::vector<DoorPassage> d = findDoorPassages(b.free, drive(), kRes, DoorPassageOptions{});
  ASSERT_EQ(d.size(), 3u);
  // In the order passed: door A, door B, the opening; each measured wall to wall across the travel direction.
  EXPECT_NEAR(d[0].width, 0.9, 0.06);
  EXPECT_NEAR(d[1].width, 0.9, 0.06);
  EXPECT_NEAR(d[2].width, 1.3, 0.06);
  EXPECT_NEAR(d[0].centre.x * kRes, 3.45, 0.05);
  EXPECT_NEAR(d[0].centre.y * kRes, 7.9, 0.25);
  EXPECT_NEAR(d[1].centre.x * kRes, 9.45, 0.05);
  EXPECT_NEAR(d[2].centre.x * kRes, 12.1, 0.25);
  EXPECT_NEAR(d[2].centre.y * kRes, 3.65, 0.05);
  // The chord of door A runs along the wall from jamb to jamb (x 3..3.9 m).
  EXPECT_NEAR(std::min(d[0].a.x, d[0].b.x) * kRes, 2.975, 0.06);
  EXPECT_NEAR(std::max(d[0].a.x, d[0].b.x) * kRes, 3.9, 0.06);
  for (const DoorPassage& p : d) EXPECT_EQ(p.passes, 1);
  // Back and forth through door A: one door passed twice.
  const std::vector<DoorPassage> twice =
      findDoorPassages(b.free, poses({{c(3.45), c(4.0)}, {c(3.45), c(9.0)}, {c(3.5), c(9.5)}, {c(3.5), c(4.0)}}), kRes, {});
  ASSERT_EQ(twice.size(), 1u);
  EXPECT_EQ(twice[0].passes, 2);
  // The geometry finds the two doors and not the opening, wider than its widest door.
  const std::vector<CriticalLine> lines = findDoorways(b.free, kRes, DoorwayGeometryOptions{});
  ASSERT_EQ(lines.size(), 2u);
  for (const CriticalLine& l : lines) EXPECT_NEAR(l.width, 0.9, 0.06);
}

TEST(DoorPassages, NoPassageWhereThePathTurnsBackOrTheOpeningIsOutOfRange) {
  const Building b = makeBuilding();
  // Into door A's opening and back into room A.
  EXPECT_TRUE(findDoorPassages(b.free, poses({{c(3.45), c(5.0)}, {c(3.45), c(7.9)}, {c(3.45), c(5.0)}}), kRes, {}).empty());
  // Along the corridor only: no narrow stretch.
  EXPECT_TRUE(findDoorPassages(b.free, poses({{c(1.5), c(9.0)}, {c(18.5), c(9.0)}}), kRes, {}).empty());
  // A jump of more than 3 m between two poses is a gap: nothing is passed across it.
  EXPECT_TRUE(findDoorPassages(b.free, {{c(3.45), c(4.0)}, {c(3.45), c(8.9)}}, kRes, {}).empty());
  // The opening is wider than door_passage_max_width 1.2 m; the doors are narrower than min_width 1.0 m.
  DoorPassageOptions narrow;
  narrow.max_width = 1.2;
  EXPECT_EQ(findDoorPassages(b.free, drive(), kRes, narrow).size(), 2u);
  DoorPassageOptions wide;
  wide.min_width = 1.0;
  EXPECT_EQ(findDoorPassages(b.free, drive(), kRes, wide).size(), 1u);
  // A stretch longer than max_length (the 0.2 m walls with the chords' slant: < 0.5 m) is a corridor, no door.
  DoorPassageOptions short_stretch;
  short_stretch.max_length = 0.05;
  EXPECT_TRUE(findDoorPassages(b.free, drive(), kRes, short_stretch).empty());
}

TEST(DoorPassages, ThreeDoorwayNodesEachBetweenTheRightTwoSpaces) {
  const Building b = makeBuilding();
  const TopologyOptions o;
  // Without the path: the geometry's two doors; rooms B and C are one space or joined directly.
  const TopologyResult without = buildTopology(b.labels, kRes, o);
  EXPECT_TRUE(without.door_passages.empty());
  EXPECT_EQ(doorwaysBetween(without.graph), (std::multiset<std::string>{"A|corridor", "B|corridor"}));
  // With the path: a doorway node at each of the three doors it went through, each between the right two spaces.
  const TopologyResult with = buildTopology(b.labels, kRes, o, nullptr, {0, 0}, drive());
  EXPECT_EQ(with.door_passages.size(), 3u);
  EXPECT_EQ(doorwaysBetween(with.graph), (std::multiset<std::string>{"A|corridor", "B|corridor", "B|C"}));
  int rooms = 0, corridors = 0;
  for (const GraphNode& n : with.graph.nodes) rooms += n.label == kRoom, corridors += n.label == kCorridor;
  EXPECT_EQ(rooms, 3);
  EXPECT_EQ(corridors, 1);
  EXPECT_EQ(with.graph.nodes.size(), 7u);
  EXPECT_EQ(with.graph.edges.size(), 6u);
  // The opening's doorway runs across it wall to wall: every cell of the 1.3 m gap's column at x 12.1 m.
  EXPECT_EQ(cv::countNonZero(with.labels(cv::Rect(ci(12.1), ci(3), 1, ci(1.3))) == kDoor), ci(1.3));
  // Off: as without the path.
  TopologyOptions off;
  off.door_passages.enabled = false;
  EXPECT_EQ(doorwaysBetween(buildTopology(b.labels, kRes, off, nullptr, {0, 0}, drive()).graph),
            doorwaysBetween(without.graph));
}

TEST(DoorPassages, OptionsAreCheckedAgainstEachOther) {
  TopologyOptions o;
  o.door_passages.min_width = 1.5;
  o.door_passages.max_width = 1.0;
  EXPECT_THROW(topologyOptionSchema().validate(o, "t.ini", "topology"), InputError);
  o.door_passages.max_width = 1.5;
  EXPECT_NO_THROW(topologyOptionSchema().validate(o, "t.ini", "topology"));
}

TEST(DoorPassages, ARoomEnteredWhereTheMapShowsNoWallGetsItsDoorway) {
  // A corridor (x 1..19 m, y 8..10 m) and room D above it (x 5..11 m, y 3..8 m) open onto it along 3 m (x 6..9 m):
  // the wall between them was seen in part only. The classifier labels room and corridor.
  cv::Mat labels(ci(11), ci(20), CV_8U, cv::Scalar(places::kNoLabel));
  labels(cv::Rect(cv::Point(ci(1), ci(8)), cv::Point(ci(19), ci(10)))).setTo(kCorridor);
  labels(cv::Rect(cv::Point(ci(5), ci(3)), cv::Point(ci(11), ci(7.8)))).setTo(kRoom);
  labels(cv::Rect(cv::Point(ci(6), ci(7.8)), cv::Point(ci(9), ci(8)))).setTo(kRoom);
  const std::vector<cv::Point2d> into = poses({{c(2), c(9)}, {c(7.5), c(9)}, {c(7.5), c(5)}, {c(7.5), c(9)}, {c(18), c(9)}});
  const TopologyOptions o;
  const TopologyResult without = buildTopology(labels, kRes, o);
  EXPECT_TRUE(doorwaysBetween(without.graph).empty());
  // The opening is too wide for a door passage; the step from the corridor into the room is a room entry.
  const TopologyResult with = buildTopology(labels, kRes, o, nullptr, {0, 0}, into);
  EXPECT_TRUE(with.door_passages.empty());
  ASSERT_EQ(with.room_entries.size(), 1u);  // in and out at the same place: one entry
  EXPECT_NEAR(with.room_entries[0].x * kRes, 7.5, 0.1);
  EXPECT_NEAR(with.room_entries[0].y * kRes, 7.95, 0.3);
  int door_nodes = 0;
  for (const GraphNode& n : with.graph.nodes) door_nodes += n.label == kDoor;
  EXPECT_EQ(door_nodes, 1);
  // The doorway: room cells within door_passage_depth (0.25 m) of the corridor, door_passage_max_width (1.4 m)
  // along the border around the step.
  const int cells = cv::countNonZero(with.labels == kDoor);
  EXPECT_GT(cells, 0.9 * ci(1.4) * ci(0.25));
  EXPECT_LT(cells, 1.2 * ci(1.4) * (ci(0.25) + 1));
  // A path that dips 0.5 m into the room and out (it runs along the border: door_passage_entry_depth is 1 m) makes
  // no entry; with entry_depth 0.4 m it does.
  const std::vector<cv::Point2d> dip = poses({{c(2), c(9)}, {c(7.5), c(9)}, {c(7.5), c(7.5)}, {c(7.5), c(9)}, {c(18), c(9)}});
  EXPECT_TRUE(buildTopology(labels, kRes, o, nullptr, {0, 0}, dip).room_entries.empty());
  TopologyOptions shallow;
  shallow.door_passages.entry_depth = 0.4;
  EXPECT_EQ(buildTopology(labels, kRes, shallow, nullptr, {0, 0}, dip).room_entries.size(), 1u);
  // Along the corridor only, or with room entries off: no doorway.
  EXPECT_TRUE(buildTopology(labels, kRes, o, nullptr, {0, 0}, poses({{c(2), c(9)}, {c(18), c(9)}})).room_entries.empty());
  TopologyOptions off;
  off.door_passages.room_entries = false;
  const TopologyResult no_entries = buildTopology(labels, kRes, off, nullptr, {0, 0}, into);
  EXPECT_TRUE(no_entries.room_entries.empty());
  EXPECT_EQ(cv::countNonZero(no_entries.labels == kDoor), 0);
}

// Scale (issue 35, item 3): buildTopology's `crop` (gridtopo-topology works on the box of the labelled cells) gives
// the whole map's topology: the same graph, door passages, room entries, labels, segmentation and overlay as without
// it, on a building placed at an odd offset in a larger empty map (the box then starts off the 2 x 2 blocks of
// the region numbering unless it is aligned, and the routes' simplification sees other absolute coordinates).
TEST(DoorPassages, CropToTheLabelledBoxGivesTheWholeMapsTopology) {
  const Building b = makeBuilding();
  const cv::Point at(37, 23);
  cv::Mat labels(b.labels.rows + 91, b.labels.cols + 140, CV_8U, cv::Scalar(places::kNoLabel));
  b.labels.copyTo(labels(cv::Rect(at, b.labels.size())));
  std::vector<cv::Point2d> path;
  for (const cv::Point2d& p : drive()) path.push_back(p + cv::Point2d(at));
  const TopologyOptions o;
  const cv::Point2d origin(-3.5, 12.25);
  const TopologyResult whole = buildTopology(labels, kRes, o, nullptr, origin, path, false);
  const TopologyResult part = buildTopology(labels, kRes, o, nullptr, origin, path, true);
  EXPECT_EQ(whole.frame, cv::Rect(cv::Point(), labels.size()));
  EXPECT_LT(part.frame.area(), labels.size().area() / 2);  // the box, not the map
  EXPECT_EQ(part.frame.x % 2, 0);
  EXPECT_EQ(part.frame.y % 2, 0);
  EXPECT_EQ(part.labels.size(), part.frame.size());
  EXPECT_EQ(part.map_size, labels.size());
  ASSERT_EQ(whole.door_passages.size(), 3u);
  ASSERT_EQ(part.door_passages.size(), whole.door_passages.size());
  for (std::size_t i = 0; i < whole.door_passages.size(); ++i) {
    // The chord's ends come from the path's samples (doubles in the part's frame): equal up to rounding.
    EXPECT_LT(cv::norm(part.door_passages[i].a - whole.door_passages[i].a), 1e-9);
    EXPECT_LT(cv::norm(part.door_passages[i].b - whole.door_passages[i].b), 1e-9);
    EXPECT_EQ(part.door_passages[i].centre, whole.door_passages[i].centre);
  }
  EXPECT_EQ(part.room_entries, whole.room_entries);
  const auto same = [](const cv::Mat& a, const cv::Mat& b) {
    return a.size() == b.size() && a.type() == b.type() && cv::countNonZero(a.reshape(1) != b.reshape(1)) == 0;
  };
  EXPECT_TRUE(same(part.inMap(part.labels, places::kNoLabel), whole.labels));
  // On the box the segmentation is held in 16 bits (its ids fit); the same ids.
  ASSERT_EQ(part.segmentation.type(), CV_16U);
  ASSERT_EQ(whole.segmentation.type(), CV_32S);
  cv::Mat part_segmentation;
  part.inMap(part.segmentation, 0).convertTo(part_segmentation, CV_32S);
  EXPECT_TRUE(same(part_segmentation, whole.segmentation));
  // The labels it was given, kept as runs in the map's frame (labels_before_correction.png).
  EXPECT_TRUE(same(part.labels_classified.image(), labels));
  EXPECT_TRUE(whole.labels_classified.empty());
  EXPECT_TRUE(same(part.inMap(part.regions.ids, 0), whole.regions.ids));
  ASSERT_EQ(part.graph.nodes.size(), whole.graph.nodes.size());
  EXPECT_EQ(part.graph.rows, whole.graph.rows);
  EXPECT_EQ(part.graph.cols, whole.graph.cols);
  for (std::size_t i = 0; i < whole.graph.nodes.size(); ++i) {
    const GraphNode &p = part.graph.nodes[i], &w = whole.graph.nodes[i];
    EXPECT_EQ(p.id, w.id);
    EXPECT_EQ(p.label, w.label);
    EXPECT_EQ(p.cells, w.cells);
    EXPECT_EQ(p.centroid_px, w.centroid_px);  // bit for bit
    EXPECT_EQ(p.centroid_m, w.centroid_m);
    EXPECT_EQ(p.bbox_px, w.bbox_px);
    EXPECT_EQ(p.anchor_px, w.anchor_px);
    EXPECT_EQ(p.anchor_m, w.anchor_m);
    EXPECT_EQ(p.centroid_inside, w.centroid_inside);
  }
  ASSERT_EQ(part.graph.edges.size(), whole.graph.edges.size());
  for (std::size_t i = 0; i < whole.graph.edges.size(); ++i) {
    const GraphEdge &p = part.graph.edges[i], &w = whole.graph.edges[i];
    EXPECT_EQ(std::make_pair(p.a, p.b), std::make_pair(w.a, w.b));
    EXPECT_EQ(p.border_cells, w.border_cells);
    EXPECT_EQ(p.contact_px, w.contact_px);
    EXPECT_EQ(p.path_px, w.path_px);
  }
  // The outputs draw the whole map either way.
  places::OccupancyImage occ;
  occ.resolution = kRes;
  occ.cells = cv::Mat(labels.size(), CV_8U, cv::Scalar(places::kOccupied));
  occ.cells.setTo(places::kFree, labels != places::kNoLabel);
  EXPECT_TRUE(same(renderOverlay(occ, part.labels, part.regions, part.graph, 2, &part.door_passages, part.frame.tl()),
                   renderOverlay(occ, whole.labels, whole.regions, whole.graph, 2, &whole.door_passages)));
  EXPECT_TRUE(same(segmentationImage16(part_segmentation), segmentationImage16(whole.segmentation)));
  EXPECT_TRUE(same(colourSegmentation(part_segmentation), colourSegmentation(whole.segmentation)));
}
