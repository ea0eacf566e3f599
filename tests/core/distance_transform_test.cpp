// preciseDistance (distance_transform.h): bit for bit the OpenCV call it replaces on maps up to a few thousand cells a
// side, and exact (the float of the root of the integer squared distance) beyond, where OpenCV's float squares err.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "gridtopo/core/distance_transform.h"

using gridtopo::preciseDistance;

namespace {
// Number of cells whose floats differ in any bit.
int bitDifferences(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != CV_32F || b.type() != CV_32F) return -1;
  int n = 0;
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x) n += std::memcmp(a.ptr<float>(y) + x, b.ptr<float>(y) + x, sizeof(float)) != 0;
  return n;
}

// `rows` x `cols` cells, each zero with probability `zero_share`, else 255 (drawn from `rng` row by row).
cv::Mat randomZeros(cv::RNG& rng, int rows, int cols, double zero_share) {
  cv::Mat mask(rows, cols, CV_8U);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) mask.at<unsigned char>(y, x) = rng.uniform(0.0, 1.0) < zero_share ? 0 : 255;
  return mask;
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
}

namespace {
// The exact distance, by brute force over the zero cells: the float of the root of the integer squared distance.
cv::Mat bruteForceDistance(const cv::Mat& mask) {
  std::vector<cv::Point> zeros;
  for (int y = 0; y < mask.rows; ++y)
    for (int x = 0; x < mask.cols; ++x)
      if (!mask.at<unsigned char>(y, x)) zeros.emplace_back(x, y);
  cv::Mat d(mask.size(), CV_32F);
  for (int y = 0; y < mask.rows; ++y)
    for (int x = 0; x < mask.cols; ++x) {
      long long best = -1;
      for (const cv::Point& z : zeros) {
        const long long dx = x - z.x, dy = y - z.y, e = dx * dx + dy * dy;
        if (best < 0 || e < best) best = e;
      }
      d.at<float>(y, x) = static_cast<float>(std::sqrt(static_cast<double>(best)));
    }
  return d;
}
}  // namespace

// Beyond 4 096 cells a side OpenCV 4.6's float squares are rounded and its result goes wrong (zero cells at 1, up
// to 2.8 cells off on the hospital's 10 079-column map); ours stays exact.
TEST(DistanceTransform, ExactOnMapsWiderAndTallerThan4096Cells) {
  cv::Mat tall(5003, 3, CV_8U, cv::Scalar(255)), wide(3, 5003, CV_8U, cv::Scalar(255));
  tall.at<unsigned char>(0, 1) = 0;
  wide.at<unsigned char>(2, 0) = 0;
  EXPECT_EQ(bitDifferences(preciseDistance(tall), bruteForceDistance(tall)), 0);
  EXPECT_EQ(bitDifferences(preciseDistance(wide), bruteForceDistance(wide)), 0);
  // A strip of a large map: free runs between walls and specks, past column 4 096.
  std::mt19937 rng(11);
  cv::Mat strip(7, 4700, CV_8U, cv::Scalar(255));
  for (int k = 0; k < 900; ++k)
    strip.at<unsigned char>(static_cast<int>(rng() % 7), static_cast<int>(rng() % 4700)) = 0;
  strip.colRange(4090, 4110).setTo(255);  // a gap across the 4 096 boundary
  const cv::Mat exact = bruteForceDistance(strip), ours = preciseDistance(strip);
  EXPECT_EQ(bitDifferences(ours, exact), 0);
  for (int y = 0; y < strip.rows; ++y)
    for (int x = 0; x < strip.cols; ++x)
      if (!strip.at<unsigned char>(y, x)) {
        ASSERT_EQ(ours.at<float>(y, x), 0.f) << x << "," << y;
      }
  // Two far corners of a map larger than 4 096 cells both ways: no zero in most rows and columns.
  cv::Mat corners(4500, 4700, CV_8U, cv::Scalar(255));
  corners.at<unsigned char>(0, 0) = corners.at<unsigned char>(4499, 4699) = 0;
  const cv::Mat c = preciseDistance(corners);
  for (const cv::Point p : {cv::Point(0, 0), cv::Point(4699, 4499), cv::Point(4699, 0), cv::Point(2000, 3000),
                            cv::Point(4100, 4400), cv::Point(4698, 4499)}) {
    const double e = std::min(std::hypot(p.x, p.y), std::hypot(4699.0 - p.x, 4499.0 - p.y));
    EXPECT_EQ(c.at<float>(p), static_cast<float>(e)) << p;
  }
}

// withinDistance is the threshold of preciseDistance, cell for cell, at reaches around the robot radius (including
// the exact roots of integers and the half-cell steps the map preparation uses) and on masks with long gaps.
TEST(DistanceTransform, WithinDistanceIsTheThresholdOfThePreciseDistance) {
  cv::RNG rng(11);
  for (int trial = 0; trial < 44; ++trial) {
    // The last trials wider than a block of the column pass (1024 columns), at an odd width.
    const int rows = 1 + rng.uniform(0, 160), cols = trial < 40 ? 1 + rng.uniform(0, 220) : 2049 + rng.uniform(0, 700);
    const double density = trial % 4 == 0 ? 0.001 : trial % 4 == 1 ? 0.01 : trial % 4 == 2 ? 0.1 : 0.5;
    const cv::Mat mask = randomZeros(rng, rows, cols, density);
    const cv::Mat d = gridtopo::preciseDistance(mask);
    // 0.3 / 0.05 is 5.999999999999999 in doubles, 6 as cv::compare's float threshold.
    for (double r : {0.0, 1.0, 1.5, std::sqrt(2.0), 2.0, 5.0, 0.3 / 0.05, 0.3 / 0.05 + 0.5, 6.5, std::sqrt(50.0), 7.0,
                     std::nextafter(7.0, 0.0), 12.3, 30.0}) {
      const cv::Mat expected = d <= r;  // as the map preparation wrote it
      const cv::Mat got = gridtopo::withinDistance(mask, r);
      ASSERT_EQ(cv::countNonZero(got != expected), 0) << "trial " << trial << " r " << r;
    }
  }
  // No zero cell: nothing is within any distance; all zero: everything within 0.
  EXPECT_EQ(cv::countNonZero(gridtopo::withinDistance(cv::Mat(30, 40, CV_8U, cv::Scalar(255)), 10.0)), 0);
  EXPECT_EQ(cv::countNonZero(gridtopo::withinDistance(cv::Mat(30, 40, CV_8U, cv::Scalar(0)), 0.0)), 1200);
  // A reach beyond the byte columns falls back to the float image, with the same cells.
  cv::Mat big(300, 700, CV_8U, cv::Scalar(255));
  big.at<unsigned char>(10, 20) = 0;
  cv::Mat expected;
  cv::compare(gridtopo::preciseDistance(big), 400.0, expected, cv::CMP_LE);
  EXPECT_EQ(cv::countNonZero(gridtopo::withinDistance(big, 400.0) != expected), 0);
}

// nearestZero: every cell's nearest zero cell is a zero cell at exactly preciseDistance's distance (the float of
// the root of the same squared distance), on random masks from sparse to dense and on a map wider than 4 096
// cells; none when the mask has no zero cell.
TEST(DistanceTransform, NearestZeroIsAtThePreciseDistance) {
  cv::RNG rng(5);
  const auto check = [](const cv::Mat& mask) {
    const cv::Mat near = gridtopo::nearestZero(mask);
    const cv::Mat d = gridtopo::preciseDistance(mask);
    for (int y = 0; y < mask.rows; ++y)
      for (int x = 0; x < mask.cols; ++x) {
        const int i = near.at<int>(y, x);
        ASSERT_GE(i, 0);
        const int nx = i % mask.cols, ny = i / mask.cols;
        ASSERT_EQ(mask.at<unsigned char>(ny, nx), 0) << "(" << x << ", " << y << ")";
        const long long dx = nx - x, dy = ny - y;
        ASSERT_EQ(static_cast<float>(std::sqrt(static_cast<double>(dx * dx + dy * dy))), d.at<float>(y, x))
            << "(" << x << ", " << y << ")";
      }
  };
  for (int trial = 0; trial < 30; ++trial) {
    const int rows = 1 + rng.uniform(0, 120), cols = 1 + rng.uniform(0, 150);
    const double density = trial % 3 == 0 ? 0.002 : trial % 3 == 1 ? 0.05 : 0.5;
    cv::Mat mask = randomZeros(rng, rows, cols, density);
    mask.at<unsigned char>(rng.uniform(0, rows), rng.uniform(0, cols)) = 0;  // at least one
    check(mask);
  }
  cv::Mat wide(3, 5000, CV_8U, cv::Scalar(255));
  wide.at<unsigned char>(0, 4900) = 0, wide.at<unsigned char>(2, 7) = 0;
  check(wide);
  EXPECT_EQ(cv::countNonZero(gridtopo::nearestZero(cv::Mat(20, 30, CV_8U, cv::Scalar(255))) != -1), 0);
}

// preciseDistanceAt is preciseDistance at one cell, the same float, near the borders, at zero cells and on a mask
// without any zero cell.
TEST(DistanceTransform, PreciseDistanceAtOneCellIsTheImagesValue) {
  cv::RNG rng(17);
  for (int trial = 0; trial < 30; ++trial) {
    const int rows = 1 + rng.uniform(0, 90), cols = 1 + rng.uniform(0, 120);
    const double density = trial % 3 == 0 ? 0.0 : trial % 3 == 1 ? 0.01 : 0.3;
    const cv::Mat mask = randomZeros(rng, rows, cols, density);
    const cv::Mat d = gridtopo::preciseDistance(mask);
    for (int k = 0; k < 200; ++k) {
      const cv::Point p(rng.uniform(0, cols), rng.uniform(0, rows));
      ASSERT_EQ(gridtopo::preciseDistanceAt(mask, p), d.at<float>(p)) << "trial " << trial << " at " << p;
      // Searched no further than a ring: the same value within it, +infinity beyond.
      const int ring = rng.uniform(0, 12);
      const float near = gridtopo::preciseDistanceAt(mask, p, ring);
      if (d.at<float>(p) <= ring) ASSERT_EQ(near, d.at<float>(p)) << "trial " << trial << " at " << p;
      else ASSERT_TRUE(near > ring) << "trial " << trial << " at " << p << " ring " << ring;
    }
  }
}
