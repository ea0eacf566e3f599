// label_runs.h: a label image as runs per row, placed in a larger image, and back.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "gridtopo/places/labelling.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/label_runs.h"

using gridtopo::topology::LabelRuns;

TEST(LabelRuns, GiveTheImageBackInItsPlace) {
  cv::RNG rng(7);
  cv::Mat labels(41, 57, CV_8U);
  // Runs of random lengths of the three labels and of cells without one (kNoLabel and other values).
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols;) {
      const int len = rng.uniform(1, 9);
      const int v = rng.uniform(0, 5);
      const unsigned char value = v < 3 ? static_cast<unsigned char>(v) : v == 3 ? gridtopo::places::kNoLabel : 200;
      for (int k = 0; k < len && x < labels.cols; ++k, ++x) labels.at<unsigned char>(y, x) = value;
    }
  cv::Mat expected = labels.clone();
  expected.setTo(gridtopo::places::kNoLabel, labels >= gridtopo::places::kNumLabels);
  const LabelRuns same_frame = LabelRuns::of(labels);
  EXPECT_EQ(same_frame.size, labels.size());
  EXPECT_EQ(cv::norm(same_frame.image(gridtopo::places::kNoLabel), expected, cv::NORM_INF), 0.0);
  EXPECT_LT(same_frame.runs.size(), static_cast<std::size_t>(cv::countNonZero(labels < 3)));

  // Placed at (6, 9) in a 80 x 70 image: every cell outside is the fill.
  const LabelRuns placed = LabelRuns::of(labels, {6, 9}, {80, 70});
  cv::Mat whole(70, 80, CV_8U, cv::Scalar(gridtopo::places::kNoLabel));
  expected.copyTo(whole(cv::Rect(6, 9, labels.cols, labels.rows)));
  EXPECT_EQ(cv::norm(placed.image(gridtopo::places::kNoLabel), whole, cv::NORM_INF), 0.0);
  // A row through a code table, as the outputs write it.
  std::vector<unsigned char> row(80);
  placed.row(20, row.data(), 0, [](unsigned char l) { return static_cast<unsigned char>(10 + l); });
  for (int x = 0; x < 80; ++x) {
    const unsigned char w = whole.at<unsigned char>(20, x);
    EXPECT_EQ(row[static_cast<std::size_t>(x)], w < 3 ? 10 + w : 0) << x;
  }
  EXPECT_TRUE(LabelRuns().empty());
}
