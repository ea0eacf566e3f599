// Regions (8-connected cells of one place label) and their border lengths on hand-made label images.
#include <gtest/gtest.h>

#include <map>
#include <opencv2/imgproc.hpp>
#include <random>
#include <utility>

#include "gridtopo/topology/regions.h"

using namespace gridtopo::topology;

namespace {
constexpr unsigned char N = 255;  // no label
}

TEST(Regions, EightConnectedCellsOfOneLabelAndTheirStatistics) {
  const cv::Mat labels = (cv::Mat_<unsigned char>(5, 6) <<  //
                              0, 0, N, 1, 1, N,               //
                              0, N, N, N, 1, N,               //
                              N, 0, N, 2, N, N,               // (2,1) joins room A diagonally; (2,3) touches (1,4)
                              N, N, N, N, N, 0,               //
                              7, N, 0, 0, N, 0);              // 7: no label either
  const RegionMap rm = extractRegions(labels, 0.5);
  ASSERT_EQ(rm.ids.type(), CV_32S);
  ASSERT_EQ(rm.ids.size(), labels.size());
  ASSERT_EQ(rm.regions.size(), 5u);  // rooms A, B, C; one corridor; one doorway

  // Ids are 1-based indices into regions, grouped by label (rooms, then corridors, then doorways).
  for (std::size_t i = 0; i < rm.regions.size(); ++i) EXPECT_EQ(rm.regions[i].id, static_cast<int>(i) + 1);
  EXPECT_EQ(rm.regions[0].label, 0);
  EXPECT_EQ(rm.regions[1].label, 0);
  EXPECT_EQ(rm.regions[2].label, 0);
  EXPECT_EQ(rm.regions[3].label, 1);
  EXPECT_EQ(rm.regions[4].label, 2);

  // Room A: the diagonal step (1,0)-(2,1) keeps it one region.
  const int a = rm.ids.at<int>(0, 0);
  ASSERT_GT(a, 0);
  for (auto [r, c] : {std::pair{0, 1}, {1, 0}, {2, 1}}) EXPECT_EQ(rm.ids.at<int>(r, c), a) << r << "," << c;
  const Region& ra = rm.region(a);
  EXPECT_EQ(ra.label, 0);
  EXPECT_EQ(ra.cells, 4);
  EXPECT_DOUBLE_EQ(ra.area_m2, 1.0);  // 4 cells of 0.25 m²
  EXPECT_DOUBLE_EQ(ra.centroid.x, 0.5);   // columns 0, 1, 0, 1
  EXPECT_DOUBLE_EQ(ra.centroid.y, 0.75);  // rows 0, 0, 1, 2
  EXPECT_EQ(ra.bbox, cv::Rect(0, 0, 2, 3));

  // Room B (vertical pair on the right) and room C (pair at the bottom) are separate regions.
  const int b = rm.ids.at<int>(3, 5), c = rm.ids.at<int>(4, 2);
  EXPECT_EQ(rm.ids.at<int>(4, 5), b);
  EXPECT_EQ(rm.ids.at<int>(4, 3), c);
  EXPECT_NE(b, a);
  EXPECT_NE(c, a);
  EXPECT_NE(b, c);
  EXPECT_EQ(rm.region(b).cells, 2);
  EXPECT_EQ(rm.region(b).bbox, cv::Rect(5, 3, 1, 2));
  EXPECT_EQ(rm.region(c).bbox, cv::Rect(2, 4, 2, 1));
  EXPECT_DOUBLE_EQ(rm.region(c).centroid.x, 2.5);
  EXPECT_DOUBLE_EQ(rm.region(c).centroid.y, 4.0);

  // The corridor and the doorway: diagonal neighbours of different labels stay separate regions.
  const Region& corridor = rm.regions[3];
  EXPECT_EQ(corridor.cells, 3);
  EXPECT_EQ(rm.ids.at<int>(0, 3), corridor.id);
  EXPECT_EQ(rm.ids.at<int>(1, 4), corridor.id);
  const Region& door = rm.regions[4];
  EXPECT_EQ(door.cells, 1);
  EXPECT_EQ(rm.ids.at<int>(2, 3), door.id);
  EXPECT_DOUBLE_EQ(door.area_m2, 0.25);

  // Unlabelled cells (255 and 7) belong to no region; labelled cells all do.
  for (int r = 0; r < labels.rows; ++r)
    for (int col = 0; col < labels.cols; ++col)
      EXPECT_EQ(rm.ids.at<int>(r, col) > 0, labels.at<unsigned char>(r, col) <= 2) << r << "," << col;

  // Borders: only the corridor and the doorway touch (one diagonal pair).
  const auto adj = regionAdjacency(rm.ids);
  ASSERT_EQ(adj.size(), 1u);
  EXPECT_EQ(adj.begin()->first, std::make_pair(corridor.id, door.id));
  EXPECT_EQ(adj.begin()->second, 1);
}

TEST(Regions, EmptyAndUnlabelledImagesHaveNoRegions) {
  const RegionMap none = extractRegions(cv::Mat(4, 3, CV_8U, cv::Scalar(N)), 0.05);
  EXPECT_TRUE(none.regions.empty());
  EXPECT_EQ(cv::countNonZero(none.ids), 0);
  EXPECT_TRUE(regionAdjacency(none.ids).empty());
  const RegionMap all = extractRegions(cv::Mat(4, 3, CV_8U, cv::Scalar(1)), 0.1);
  ASSERT_EQ(all.regions.size(), 1u);
  EXPECT_EQ(all.regions[0].cells, 12);
  EXPECT_NEAR(all.regions[0].area_m2, 0.12, 1e-12);
  EXPECT_EQ(all.regions[0].bbox, cv::Rect(0, 0, 3, 4));
}

TEST(Regions, RejectsNon8BitLabels) {
  EXPECT_THROW(extractRegions(cv::Mat(2, 2, CV_32S, cv::Scalar(0)), 0.05), cv::Exception);
}

TEST(Regions, AdjacencyCountsEachEightNeighbourPairOnce) {
  const cv::Mat ids = (cv::Mat_<int>(3, 3) <<  //
                           1, 1, 2,            //
                           1, 3, 2,            //
                           0, 3, 3);
  const auto adj = regionAdjacency(ids);
  const std::map<std::pair<int, int>, int> expected = {{{1, 2}, 2}, {{1, 3}, 4}, {{2, 3}, 4}};
  EXPECT_EQ(adj, expected);
  // Symmetric in the ids: swapping ids 1 and 3 swaps the keys, the counts follow.
  const cv::Mat swapped = (cv::Mat_<int>(3, 3) <<  //
                               3, 3, 2,            //
                               3, 1, 2,            //
                               0, 1, 1);
  const std::map<std::pair<int, int>, int> expected_swapped = {{{2, 3}, 2}, {{1, 3}, 4}, {{1, 2}, 4}};
  EXPECT_EQ(regionAdjacency(swapped), expected_swapped);
  // Cells touching only at a corner are neighbours, along either diagonal.
  const cv::Mat diag = (cv::Mat_<int>(2, 2) << 5, 0, 0, 9);
  EXPECT_EQ(regionAdjacency(diag), (std::map<std::pair<int, int>, int>{{{5, 9}, 1}}));
  const cv::Mat anti = (cv::Mat_<int>(2, 2) << 0, 5, 9, 0);
  EXPECT_EQ(regionAdjacency(anti), (std::map<std::pair<int, int>, int>{{{5, 9}, 1}}));
  // Zero and negative ids are no region.
  const cv::Mat neg = (cv::Mat_<int>(1, 3) << 4, -1, 4);
  EXPECT_TRUE(regionAdjacency(neg).empty());
}

// extractRegions scans the image once with union-find; the regions (ids, order, statistics) must be those of one
// cv::connectedComponentsWithStats per label, the implementation it replaced, kept here as the reference.
TEST(Regions, SameRegionsAsOpenCvConnectedComponentsPerLabel) {
  std::mt19937 rng(11);
  std::size_t regions = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const int rows = 1 + static_cast<int>(rng() % (trial < 6 ? 40 : 900));
    const int cols = 1 + static_cast<int>(rng() % (trial < 6 ? 40 : 1100));
    cv::Mat labels(rows, cols, CV_8U, cv::Scalar(N));
    for (int k = 0; k < 60; ++k) {  // blobs, bars, diagonal lines and speckles of the three labels
      const cv::Point a(static_cast<int>(rng() % cols), static_cast<int>(rng() % rows));
      const cv::Point b(static_cast<int>(rng() % cols), static_cast<int>(rng() % rows));
      const cv::Scalar l(static_cast<double>(rng() % 4 == 3 ? N : rng() % 3));
      if (k % 3 == 0) cv::circle(labels, a, 1 + static_cast<int>(rng() % 60), l, cv::FILLED);
      else if (k % 3 == 1) cv::line(labels, a, b, l, 1 + static_cast<int>(rng() % 3), cv::LINE_8);
      else cv::rectangle(labels, a, b, l, cv::FILLED);
    }
    for (int k = 0; k < rows * cols / 20; ++k)
      labels.at<unsigned char>(static_cast<int>(rng() % rows), static_cast<int>(rng() % cols)) =
          static_cast<unsigned char>(rng() % 4 == 3 ? N : rng() % 3);
    const RegionMap rm = extractRegions(labels, 0.05);
    cv::Mat ids(labels.size(), CV_32S, cv::Scalar(0));
    std::vector<Region> ref;
    for (int l = 0; l < 3; ++l) {
      cv::Mat cc, stats, cents;
      const int n = cv::connectedComponentsWithStats(labels == l, cc, stats, cents, 8, CV_32S);
      const int base = static_cast<int>(ref.size());
      for (int k = 1; k < n; ++k) {
        Region r;
        r.id = base + k, r.label = l, r.cells = stats.at<int>(k, cv::CC_STAT_AREA);
        r.centroid = cv::Point2d(cents.at<double>(k, 0), cents.at<double>(k, 1));
        r.bbox = cv::Rect(stats.at<int>(k, cv::CC_STAT_LEFT), stats.at<int>(k, cv::CC_STAT_TOP),
                          stats.at<int>(k, cv::CC_STAT_WIDTH), stats.at<int>(k, cv::CC_STAT_HEIGHT));
        ref.push_back(r);
      }
      for (int y = 0; y < rows; ++y)
        for (int x = 0; x < cols; ++x)
          if (const int c = cc.at<int>(y, x)) ids.at<int>(y, x) = base + c;
    }
    ASSERT_EQ(rm.regions.size(), ref.size()) << "trial " << trial;
    EXPECT_EQ(cv::countNonZero(rm.ids != ids), 0) << "trial " << trial << ", " << rows << " x " << cols;
    for (std::size_t i = 0; i < ref.size(); ++i) {
      const Region& a = rm.regions[i];
      const Region& b = ref[i];
      ASSERT_EQ(a.id, b.id);
      EXPECT_EQ(a.label, b.label);
      EXPECT_EQ(a.cells, b.cells);
      EXPECT_EQ(a.bbox, b.bbox);
      EXPECT_EQ(a.centroid.x, b.centroid.x);  // bit for bit
      EXPECT_EQ(a.centroid.y, b.centroid.y);
      EXPECT_DOUBLE_EQ(a.area_m2, b.cells * 0.05 * 0.05);
    }
    regions += ref.size();
  }
  EXPECT_GT(regions, 5000u);  // many regions, most of them in the large images
}
