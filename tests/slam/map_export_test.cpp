// renderMap: the picture behind map_trajectory.png.
#include <gtest/gtest.h>

#include <cstdio>

#include <opencv2/core.hpp>

#include "gridtopo/slam/map_export.h"

namespace slam = gridtopo::slam;

namespace {
// The lines are anti-aliased over the grey of unknown cells (128): a pixel counts as magenta (200, 0, 200 BGR) or
// orange (0, 140, 255) when it is nearer to that colour than half way from the grey.
bool magentaish(const cv::Vec3b& p) { return p[1] < 70 && p[0] > 160 && p[2] > 160; }
bool orangeish(const cv::Vec3b& p) { return p[0] < 70 && p[2] > 190 && p[1] > 100 && p[1] < 170; }
template <class Is>
int count(const cv::Mat& img, Is is) {
  int n = 0;
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) n += is(img.at<cv::Vec3b>(y, x));
  return n;
}
}  // namespace

TEST(MapExport, WindowedClosuresMagentaGlobalOnesOrangeAndThickOnTop) {
  mrpt::maps::COccupancyGridMap2D grid(-5.0f, 5.0f, -5.0f, 5.0f, 0.05f);  // 200 x 200 cells, unknown
  std::vector<slam::ClosureLine> closures;
  closures.push_back({{-4.0, -3.0, 0.0}, {4.0, -3.0, 0.0}, false});  // a horizontal windowed closure
  closures.push_back({{-4.0, 3.0, 0.0}, {4.0, 3.0, 0.0}, true});     // a horizontal global one
  closures.push_back({{0.0, -4.5, 0.0}, {0.0, 4.5, 0.0}, false});    // a vertical windowed one crossing it
  const cv::Mat img = slam::renderMap(grid, {}, closures);
  ASSERT_EQ(img.cols, 200);
  ASSERT_EQ(img.rows, 200);
  const int magenta = count(img, magentaish), orange = count(img, orangeish);
  std::printf("magenta %d orange %d\n", magenta, orange);
  // The windowed lines about one pixel wide: 160 + 180 pixels long, less where the global line covers them; the
  // global line three wide, five with its anti-aliased edges (5 x 160), and its ring (radius 8, two wide: about
  // 2 pi 8 x 3 with the edges, less where it lies on the line).
  EXPECT_NEAR(magenta, 160 + 180 - 5, 20);
  EXPECT_NEAR(orange, 5 * 160 + 130, 50);
  // Where the vertical windowed line crosses the global one, the global one is drawn on top.
  const int row = 200 - 1 - grid.y2idx(3.0f), col = grid.x2idx(0.0f);
  EXPECT_TRUE(orangeish(img.at<cv::Vec3b>(row, col)));
  EXPECT_TRUE(magentaish(img.at<cv::Vec3b>(row + 10, col - 1)) || magentaish(img.at<cv::Vec3b>(row + 10, col)) ||
              magentaish(img.at<cv::Vec3b>(row + 10, col + 1)));
}
