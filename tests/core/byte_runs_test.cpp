// byte_runs.h: an 8-bit image as runs per row without its background, placed in a larger image, and back.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "gridtopo/core/byte_runs.h"

using gridtopo::ByteRuns;

TEST(ByteRuns, GiveTheImageBackInItsPlace) {
  cv::RNG rng(7);
  cv::Mat image(41, 57, CV_8U);
  // Runs of random lengths of five values, one of them the background.
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols;) {
      const int len = rng.uniform(1, 9);
      const unsigned char value = static_cast<unsigned char>(std::vector<int>{0, 1, 2, 205, 255}[rng.uniform(0, 5)]);
      for (int k = 0; k < len && x < image.cols; ++k, ++x) image.at<unsigned char>(y, x) = value;
    }
  const ByteRuns same_frame = ByteRuns::of(image, 205);
  EXPECT_EQ(same_frame.size, image.size());
  EXPECT_EQ(cv::norm(same_frame.image(), image, cv::NORM_INF), 0.0);
  EXPECT_LT(same_frame.runs.size(), static_cast<std::size_t>(cv::countNonZero(image != 205)));
  for (const ByteRuns::Run& r : same_frame.runs) EXPECT_NE(r.value, 205);

  // Placed at (6, 9) in a 80 x 70 image: every cell outside is the background.
  const ByteRuns placed = ByteRuns::of(image, 255, {6, 9}, {80, 70});
  cv::Mat whole(70, 80, CV_8U, cv::Scalar(255));
  image.copyTo(whole(cv::Rect(6, 9, image.cols, image.rows)));
  EXPECT_EQ(cv::norm(placed.image(), whole, cv::NORM_INF), 0.0);
  // A row through a value map, as the outputs write it.
  std::vector<unsigned char> row(80);
  placed.row(20, row.data(), [](unsigned char v) { return static_cast<unsigned char>(v < 3 ? 10 + v : 0); });
  for (int x = 0; x < 80; ++x) {
    const unsigned char w = whole.at<unsigned char>(20, x);
    EXPECT_EQ(row[static_cast<std::size_t>(x)], w < 3 ? 10 + w : 0) << x;
  }
  EXPECT_TRUE(ByteRuns().empty());
}
