// Corridor pieces for the graph (corridor_split.h): junctions and branches of synthetic corridor shapes.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>

#include <random>

#include "gridtopo/places/labelling.h"
#include "gridtopo/topology/corridor_split.h"
#include "gridtopo/topology/graph.h"
#include "gridtopo/topology/pipeline.h"

using namespace gridtopo;
using namespace gridtopo::topology;

namespace {
constexpr double kRes = 0.05;
constexpr unsigned char kRoom = 0, kCorridor = 1, kDoor = 2;

cv::Mat emptyLabels() { return cv::Mat(500, 500, CV_8U, cv::Scalar(places::kNoLabel)); }
// A corridor 2 m wide (40 cells) from a to b (cell coordinates of the centre line).
void corridor(cv::Mat& l, cv::Point a, cv::Point b) {
  cv::line(l, a, b, cv::Scalar(kCorridor), 40, cv::LINE_8);
}
int countLabel(const RegionMap& rm, int label) {
  int n = 0;
  for (const auto& r : rm.regions) n += r.label == label;
  return n;
}
}  // namespace

TEST(CorridorSplit, CrossBecomesAJunctionAndFourArms) {
  cv::Mat l = emptyLabels();
  corridor(l, {50, 250}, {450, 250});
  corridor(l, {250, 50}, {250, 450});
  const RegionMap before = extractRegions(l, kRes);
  ASSERT_EQ(countLabel(before, kCorridor), 1);
  const RegionMap after = splitCorridors(before, kRes);
  ASSERT_EQ(countLabel(after, kCorridor), 5);
  // The piece at the crossing touches the four others; no two arms touch.
  const int centre = after.ids.at<int>(250, 250);
  const TopologicalGraph g = buildGraph(after, kRes);
  int centre_edges = 0;
  for (const auto& e : g.edges) {
    EXPECT_TRUE(e.a == centre || e.b == centre) << e.a << "-" << e.b;
    centre_edges += e.a == centre || e.b == centre;
  }
  EXPECT_EQ(centre_edges, 4);
  // Every corridor cell is in exactly one piece, and the pieces cover the region.
  EXPECT_EQ(cv::countNonZero(after.ids > 0), cv::countNonZero(before.ids > 0));
  int cells = 0;
  for (const auto& r : after.regions) cells += r.cells;
  EXPECT_EQ(cells, cv::countNonZero(before.ids > 0));
  // Each arm is 8 m long outside the crossing: far above the minimum piece area.
  for (const auto& r : after.regions) EXPECT_GT(r.area_m2, 5.0);
}

TEST(CorridorSplit, TeeGivesFourPiecesStraightAndRingGiveOne) {
  cv::Mat tee = emptyLabels();
  corridor(tee, {50, 100}, {450, 100});
  corridor(tee, {250, 100}, {250, 450});
  EXPECT_EQ(countLabel(splitCorridors(extractRegions(tee, kRes), kRes), kCorridor), 4);

  cv::Mat straight = emptyLabels();
  corridor(straight, {50, 250}, {450, 250});
  // Wall recesses 1 m deep and door-wide stubs of corridor label 2 m into rooms: side branches that reach less
  // than min_branch (4 m) beyond the wall are no junctions.
  for (int x = 80; x < 420; x += 60) cv::rectangle(straight, cv::Rect(x, 270, 20, 20 + (x % 120 ? 20 : 40)),
                                                   cv::Scalar(kCorridor), cv::FILLED);
  const RegionMap s = splitCorridors(extractRegions(straight, kRes), kRes);
  EXPECT_EQ(countLabel(s, kCorridor), 1);

  cv::Mat ring = emptyLabels();
  cv::rectangle(ring, cv::Rect(60, 60, 380, 380), cv::Scalar(kCorridor), 40);
  EXPECT_EQ(countLabel(splitCorridors(extractRegions(ring, kRes), kRes), kCorridor), 1);
}

TEST(CorridorSplit, LongSideBranchIsAJunctionAndPillarsAreNot) {
  cv::Mat l = emptyLabels();
  corridor(l, {50, 250}, {450, 250});
  corridor(l, {250, 250}, {250, 420});  // 7.5 m side branch: a real T
  // Pillars (0.4 m squares) in the main corridor: holes in the region, filled for the skeleton.
  for (int x = 100; x < 420; x += 80) l(cv::Rect(x, 245, 8, 8)).setTo(places::kNoLabel);
  const RegionMap after = splitCorridors(extractRegions(l, kRes), kRes);
  EXPECT_EQ(countLabel(after, kCorridor), 4);
}

TEST(CorridorSplit, OtherRegionsSegmentationAndLabelsAreUnchanged) {
  cv::Mat l = emptyLabels();
  corridor(l, {50, 250}, {450, 250});
  corridor(l, {250, 50}, {250, 450});
  cv::rectangle(l, cv::Rect(300, 300, 150, 150), cv::Scalar(kRoom), cv::FILLED);  // a room in a corner
  cv::rectangle(l, cv::Rect(340, 268, 30, 32), cv::Scalar(kDoor), cv::FILLED);     // its door onto the corridor
  TopologyOptions off;
  off.corridor_split.enabled = false;
  const TopologyResult a = buildTopology(l, kRes, off);
  const TopologyResult b = buildTopology(l, kRes, TopologyOptions{});
  EXPECT_EQ(cv::countNonZero(a.labels != b.labels), 0);
  EXPECT_EQ(cv::countNonZero(a.segmentation != b.segmentation), 0);
  EXPECT_EQ(countLabel(a.regions, kCorridor), 1);
  EXPECT_EQ(countLabel(b.regions, kCorridor), 5);
  EXPECT_EQ(countLabel(b.regions, kRoom), 1);
  EXPECT_EQ(countLabel(b.regions, kDoor), 1);
  // The graph stays one piece: room - door - corridor arm - junction - other arms.
  EXPECT_EQ(b.graph.connectedComponents(), 1);
  EXPECT_EQ(b.graph.nodes.size(), 7u);
}

// The in-place overload (over the input's id image, the graph stage's) gives the copying one's regions and ids;
// the copying one and a shallow copy given to the in-place one leave the caller's image as it was.
TEST(CorridorSplit, InPlaceEqualsCopyAndSparesSharedImages) {
  cv::Mat l = emptyLabels();
  corridor(l, {50, 250}, {450, 250});
  corridor(l, {250, 50}, {250, 450});
  corridor(l, {50, 100}, {180, 100});                                              // a straight corridor of its own
  cv::rectangle(l, cv::Rect(300, 300, 150, 150), cv::Scalar(kRoom), cv::FILLED);  // a room in a corner
  cv::rectangle(l, cv::Rect(340, 268, 30, 32), cv::Scalar(kDoor), cv::FILLED);     // its door onto the corridor
  const RegionMap before = extractRegions(l, kRes);
  const cv::Mat ids_before = before.ids.clone();
  const RegionMap copied = splitCorridors(before, kRes);
  EXPECT_EQ(cv::countNonZero(before.ids != ids_before), 0);
  RegionMap shared = before;  // shares the id image with `before`
  const RegionMap from_shared = splitCorridors(std::move(shared), kRes);
  EXPECT_EQ(cv::countNonZero(before.ids != ids_before), 0);
  RegionMap own = before;
  own.ids = before.ids.clone();
  const int* own_data = own.ids.ptr<int>(0);
  const RegionMap in_place = splitCorridors(std::move(own), kRes);
  EXPECT_EQ(in_place.ids.ptr<int>(0), own_data);  // no second image
  ASSERT_EQ(countLabel(copied, kCorridor), 6);     // the cross's five pieces and the straight corridor
  for (const RegionMap* r : {&from_shared, &in_place}) {
    EXPECT_EQ(cv::countNonZero(r->ids != copied.ids), 0);
    ASSERT_EQ(r->regions.size(), copied.regions.size());
    for (std::size_t i = 0; i < copied.regions.size(); ++i) {
      EXPECT_EQ(r->regions[i].id, copied.regions[i].id);
      EXPECT_EQ(r->regions[i].label, copied.regions[i].label);
      EXPECT_EQ(r->regions[i].cells, copied.regions[i].cells);
      EXPECT_EQ(r->regions[i].bbox, copied.regions[i].bbox);
    }
  }
  // Every cell of an input region is in an output region of the same label, and no other cell is.
  for (int y = 0; y < l.rows; ++y)
    for (int x = 0; x < l.cols; ++x) {
      const int a = before.ids.at<int>(y, x), b = in_place.ids.at<int>(y, x);
      ASSERT_EQ(a > 0, b > 0) << x << "," << y;
      if (a > 0) {
        ASSERT_EQ(before.region(a).label, in_place.region(b).label);
      }
    }
}

// thinZhangSuen visits only the cells next to the last removals; it must give OpenCV's skeleton cell for cell, on
// shapes that touch the image border, have holes and one-cell spurs, and with grey values either side of 128.
TEST(CorridorSplit, ThinningEqualsOpenCvZhangSuen) {
  std::mt19937 rng(7);
  int skeleton_cells = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int rows = 3 + static_cast<int>(rng() % 160), cols = 3 + static_cast<int>(rng() % 200);
    cv::Mat m(rows, cols, CV_8U, cv::Scalar(0));
    for (int k = 0; k < 12; ++k) {
      const cv::Point a(static_cast<int>(rng() % cols), static_cast<int>(rng() % rows));
      const cv::Point b(static_cast<int>(rng() % cols), static_cast<int>(rng() % rows));
      const int grey = k % 5 == 4 ? 127 + static_cast<int>(rng() % 3) : 255;  // 127 is not set, 128 and 129 are
      switch (rng() % 4) {
        case 0: cv::line(m, a, b, cv::Scalar(grey), 1 + static_cast<int>(rng() % 25)); break;
        case 1: cv::circle(m, a, 1 + static_cast<int>(rng() % 30), cv::Scalar(grey), cv::FILLED); break;
        case 2: cv::rectangle(m, a, b, cv::Scalar(grey), cv::FILLED); break;
        default: cv::circle(m, a, 1 + static_cast<int>(rng() % 8), cv::Scalar(0), cv::FILLED);  // a hole
      }
    }
    for (int k = 0; k < rows * cols / 50; ++k)  // salt and pepper
      m.at<unsigned char>(static_cast<int>(rng() % rows), static_cast<int>(rng() % cols)) ^= 255;
    cv::Mat expected;
    cv::ximgproc::thinning(m, expected, cv::ximgproc::THINNING_ZHANGSUEN);
    const cv::Mat ours = thinZhangSuen(m);
    ASSERT_EQ(ours.size(), expected.size());
    ASSERT_EQ(cv::countNonZero(ours != expected), 0) << "trial " << trial << ", " << rows << " x " << cols;
    skeleton_cells += cv::countNonZero(ours);
  }
  EXPECT_GT(skeleton_cells, 1000);  // the shapes are not all empty
}
