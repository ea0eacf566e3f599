// preciseDistance (distance_transform.h) against the OpenCV call it replaces, cell for cell and bit for bit.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cstring>
#include <random>

#include "gridtopo/topology/distance_transform.h"

using namespace gridtopo::topology;

namespace {
// Number of cells whose floats differ in any bit.
int bitDifferences(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != CV_32F || b.type() != CV_32F) return -1;
  int n = 0;
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x) n += std::memcmp(a.ptr<float>(y) + x, b.ptr<float>(y) + x, sizeof(float)) != 0;
  return n;
}

void expectSameAsOpenCv(const cv::Mat& mask, const std::string& what) {
  cv::Mat expected;
  cv::distanceTransform(mask, expected, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const cv::Mat ours = preciseDistance(mask);
  EXPECT_EQ(bitDifferences(ours, expected), 0) << what << " (" << mask.rows << " x " << mask.cols << ")";
}
}  // namespace

TEST(DistanceTransform, BitForBitOpenCvPreciseOnRandomMasks) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 30; ++trial) {
    const int rows = 1 + static_cast<int>(rng() % 300), cols = 1 + static_cast<int>(rng() % 300);
    cv::Mat m(rows, cols, CV_8U, cv::Scalar(trial % 3 == 0 ? 0 : 255));
    for (int k = 0; k < 10; ++k) {  // rooms, walls and specks; grey values count as set
      const cv::Point a(static_cast<int>(rng() % cols), static_cast<int>(rng() % rows));
      const cv::Point b(static_cast<int>(rng() % cols), static_cast<int>(rng() % rows));
      const cv::Scalar v(static_cast<double>(rng() % 3 == 0 ? 0 : 1 + rng() % 255));
      if (k % 2) cv::rectangle(m, a, b, v, cv::FILLED);
      else cv::line(m, a, b, v, 1 + static_cast<int>(rng() % 4));
    }
    for (int k = 0; k < rows * cols / 200; ++k)
      m.at<unsigned char>(static_cast<int>(rng() % rows), static_cast<int>(rng() % cols)) ^= 255;
    expectSameAsOpenCv(m, "trial " + std::to_string(trial));
  }
}

TEST(DistanceTransform, BitForBitOpenCvPreciseOnEdgeCases) {
  expectSameAsOpenCv(cv::Mat(1, 1, CV_8U, cv::Scalar(0)), "one zero cell");
  expectSameAsOpenCv(cv::Mat(1, 1, CV_8U, cv::Scalar(255)), "one set cell");
  expectSameAsOpenCv(cv::Mat(40, 70, CV_8U, cv::Scalar(255)), "no zero cell at all");
  cv::Mat column(37, 90, CV_8U, cv::Scalar(255));
  column.col(13).setTo(0);  // rows without a zero are none here, columns without one are most
  expectSameAsOpenCv(column, "one zero column");
  cv::Mat row(90, 37, CV_8U, cv::Scalar(255));
  row.row(71).setTo(0);
  expectSameAsOpenCv(row, "one zero row");
  // Longer than 4096 cells both ways: squares beyond 2^24 are rounded to float in OpenCV's tables.
  cv::Mat tall(5003, 3, CV_8U, cv::Scalar(255)), wide(3, 5003, CV_8U, cv::Scalar(255));
  tall.at<unsigned char>(0, 1) = 0;
  wide.at<unsigned char>(2, 0) = 0;
  expectSameAsOpenCv(tall, "tall");
  expectSameAsOpenCv(wide, "wide");
  cv::Mat corners(4500, 4700, CV_8U, cv::Scalar(255));
  corners.at<unsigned char>(0, 0) = corners.at<unsigned char>(4499, 4699) = 0;
  expectSameAsOpenCv(corners, "two far corners");
}
