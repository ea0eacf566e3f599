// places::openFreeSpace: the morphological opening that seals the dotted walls of SLAM maps.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "gridtopo/places/occupancy.h"

using namespace gridtopo::places;

namespace {
// Two 2 x 2 m rooms (40 x 40 cells at 5 cm) side by side, separated by a wall drawn as a dotted line (every other
// cell occupied, as SLAM draws a wall seen edge-on), plus a 1 m door in a solid wall to a third room below, and a
// one-cell free streak running from the right room into the unknown.
OccupancyImage dottedWallMap() {
  OccupancyImage occ;
  occ.resolution = 0.05;
  occ.cells = cv::Mat(100, 120, CV_8U, cv::Scalar(kUnknown));
  cv::rectangle(occ.cells, cv::Rect(5, 5, 81, 42), cv::Scalar(kOccupied), 1);
  occ.cells(cv::Rect(6, 6, 79, 40)).setTo(kFree);
  for (int r = 6; r < 46; r += 2) occ.cells.at<unsigned char>(r, 45) = kOccupied;  // dotted wall, 1-cell gaps
  cv::rectangle(occ.cells, cv::Rect(5, 46, 81, 40), cv::Scalar(kOccupied), 1);
  occ.cells(cv::Rect(6, 47, 79, 38)).setTo(kFree);
  occ.cells(cv::Rect(20, 46, 20, 1)).setTo(kFree);  // 1 m door in the solid wall
  occ.cells(cv::Rect(85, 20, 30, 1)).setTo(kFree);  // ray streak through the right wall into the unknown
  return occ;
}
int freeComponents(const OccupancyImage& occ) {
  cv::Mat cc;
  return cv::connectedComponents(occ.cells == kFree, cc, 8) - 1;
}
}  // namespace

TEST(Occupancy, OpeningSealsDottedWallsKeepsDoorsAndRemovesStreaks) {
  OccupancyImage occ = dottedWallMap();
  ASSERT_EQ(freeComponents(occ), 1);  // the three rooms and the streak leak into one another
  const std::size_t free_before = countFree(occ);
  const std::size_t removed = openFreeSpace(occ, 0.05);
  // The rooms above the door are now two (the dotted wall is sealed); the lower room stays joined through the door.
  EXPECT_EQ(freeComponents(occ), 2);
  EXPECT_EQ(occ.cells.at<unsigned char>(20, 100), kUnknown);  // the streak is gone, as unknown, not as a wall
  EXPECT_EQ(occ.cells.at<unsigned char>(46, 30), kFree);     // the door is still free
  EXPECT_EQ(occ.cells.at<unsigned char>(25, 25), kFree);     // room cores untouched
  EXPECT_EQ(countFree(occ) + removed, free_before);
  // Only the gaps of the dotted wall, the streak and the cells in the rooms' corners next to the dots can go.
  EXPECT_LT(removed, 150u);
  EXPECT_GT(removed, 40u);
}

TEST(Occupancy, OpeningRadiusBelowHalfACellDoesNothing) {
  OccupancyImage occ = dottedWallMap();
  const cv::Mat before = occ.cells.clone();
  EXPECT_EQ(openFreeSpace(occ, 0), 0u);
  EXPECT_EQ(openFreeSpace(occ, 0.02), 0u);
  EXPECT_EQ(cv::countNonZero(occ.cells != before), 0);
}

TEST(Occupancy, OpeningKeepsFreeCellsAtTheImageBorder) {
  OccupancyImage occ;
  occ.resolution = 0.05;
  occ.cells = cv::Mat(30, 30, CV_8U, cv::Scalar(kFree));  // a map cut out of a larger free area
  EXPECT_EQ(openFreeSpace(occ, 0.1), 0u);
}

TEST(Occupancy, OpeningIsOpenCVsMorphologicalOpening) {
  // openFreeSpace erodes, then dilates in place (one full-map image less than cv::morphologyEx): the same cells as
  // MORPH_OPEN with the border counted free, on random maps and radii.
  cv::RNG rng(5);
  for (int trial = 0; trial < 12; ++trial) {
    OccupancyImage occ;
    occ.resolution = 0.05;
    occ.cells = cv::Mat(40 + rng.uniform(0, 60), 40 + rng.uniform(0, 70), CV_8U);
    for (int y = 0; y < occ.cells.rows; ++y)
      for (int x = 0; x < occ.cells.cols; ++x) {
        const double u = rng.uniform(0.0, 1.0);
        occ.cells.at<unsigned char>(y, x) = u < 0.7 ? kFree : u < 0.85 ? kOccupied : kUnknown;
      }
    const double radius = 0.05 * (1 + trial % 3);
    const int r = static_cast<int>(std::lround(radius / occ.resolution));
    cv::Mat opened, expected = occ.cells.clone();
    cv::morphologyEx(occ.cells == kFree, opened, cv::MORPH_OPEN,
                     cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * r + 1, 2 * r + 1)), cv::Point(-1, -1), 1,
                     cv::BORDER_CONSTANT, cv::Scalar(255));
    const cv::Mat removed = (occ.cells == kFree) & ~opened;
    expected.setTo(kUnknown, removed);
    EXPECT_EQ(openFreeSpace(occ, radius), static_cast<std::size_t>(cv::countNonZero(removed)));
    EXPECT_EQ(cv::countNonZero(occ.cells != expected), 0) << "trial " << trial;
  }
}
