#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "gridtopo/core/error.h"
#include "gridtopo/session/label_canvas.h"
#include "test_helpers.h"

using namespace gridtopo;
using session::LabelCanvas;

TEST(LabelCanvas, BrushPaintsOnlyFreeCellsInsideTheDisc) {
  const cv::Mat plan = guitest::floorPlan();
  LabelCanvas c;
  c.reset(plan);
  // A disc of radius 3 (29 cells) fully inside room A.
  EXPECT_EQ(c.brush(40, 50, 3, 77), 29);
  EXPECT_EQ(c.code(40, 50), 77);
  EXPECT_EQ(c.code(40, 53), 77);
}

TEST(LabelCanvas, BrushDiscShapeAndWalls) {
  const cv::Mat plan = guitest::floorPlan();
  LabelCanvas c;
  c.reset(plan);
  c.brush(40, 50, 3, 77);
  EXPECT_EQ(c.code(42, 52), 77);  // distance² 8 <= 9
  EXPECT_EQ(c.code(43, 53), 0);   // distance² 18 > 9
  // On the wall of room A (row 8 is a wall line): walls are not painted, free cells around are.
  const int n = c.brush(9, 50, 2, 115);
  EXPECT_GT(n, 0);
  EXPECT_EQ(c.code(8, 50), 0);
  EXPECT_EQ(c.code(10, 50), 115);
  // free_only = false paints the wall too.
  c.brush(8, 60, 0, 179, false);
  EXPECT_EQ(c.code(8, 60), 179);
}

TEST(LabelCanvas, FloodFillStopsAtWallsAndOtherLabels) {
  const cv::Mat plan = guitest::floorPlan();
  LabelCanvas c;
  c.reset(plan);
  // Close door A with doorway paint so the fill of room A stays in room A.
  for (int col = 42; col <= 57; ++col) c.brush(75, col, 4, 179);
  const int filled = c.floodFill(40, 50, 77);
  // Room A: 81 x 61 free cells, minus the cells of its own bottom rows the doorway brush painted (none: the
  // brush at row 75 radius 4 reaches row 71, the door gap).
  EXPECT_EQ(filled, 81 * 61);
  EXPECT_EQ(c.code(12, 12), 77);
  EXPECT_EQ(c.code(40, 150), 0);  // room B untouched
  EXPECT_EQ(c.code(90, 100), 0);  // corridor untouched
  // Filling again with the same code changes nothing.
  EXPECT_EQ(c.floodFill(40, 50, 77), 0);
  // Fill on a wall: nothing.
  EXPECT_EQ(c.floodFill(8, 50, 115), 0);
}

TEST(LabelCanvas, UndoRestoresStrokesAndFillsExactly) {
  const cv::Mat plan = guitest::floorPlan();
  LabelCanvas c;
  c.reset(plan);
  const cv::Mat blank = c.codes().clone();
  c.beginStroke();
  for (int col = 20; col < 180; col += 3) c.brush(92, col, 5, 115);
  c.endStroke();
  const cv::Mat after_stroke = c.codes().clone();
  c.floodFill(40, 150, 77);
  EXPECT_EQ(c.undoDepth(), 2u);
  ASSERT_TRUE(c.undo());
  EXPECT_EQ(cv::countNonZero(c.codes() != after_stroke), 0);
  ASSERT_TRUE(c.undo());  // the whole stroke in one step
  EXPECT_EQ(cv::countNonZero(c.codes() != blank), 0);
  EXPECT_FALSE(c.undo());
  // A single dab outside a stroke is its own step.
  c.brush(40, 50, 1, 77);
  c.brush(40, 60, 1, 77);
  EXPECT_EQ(c.undoDepth(), 2u);
}

TEST(LabelCanvas, SaveLoadRoundTripInTrainingCodes) {
  guitest::TempDir tmp;
  const cv::Mat plan = guitest::floorPlan();
  LabelCanvas c;
  c.reset(plan);
  c.beginStroke();
  for (int col = 42; col <= 57; ++col) c.brush(75, col, 4, 179), c.brush(75, col + 100, 4, 179);
  c.endStroke();
  c.floodFill(40, 50, 77);
  c.floodFill(40, 150, 77);
  c.floodFill(92, 100, 115);
  const auto h = c.histogram();  // free cells per code 0, 77, 115, 179
  EXPECT_EQ(h[0], 0);
  EXPECT_EQ(h[1], 2 * 81 * 61);
  EXPECT_EQ(h[2], 181 * 25);
  EXPECT_EQ(h[3], 2 * 9 * 16);
  c.save(tmp / "labels.png");
  const cv::Mat img = cv::imread(tmp / "labels.png", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(img.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(img != c.codes()), 0);
  for (int r = 0; r < img.rows; ++r)
    for (int col = 0; col < img.cols; ++col) ASSERT_TRUE(LabelCanvas::isTrainingCode(img.at<unsigned char>(r, col)));
  LabelCanvas d;
  d.reset(plan);
  d.load(tmp / "labels.png");
  EXPECT_EQ(cv::countNonZero(d.codes() != c.codes()), 0);
}

TEST(LabelCanvas, BadLabelImagesAreRejectedWithTheirFileAndPixel) {
  guitest::TempDir tmp;
  const cv::Mat plan = guitest::floorPlan();
  LabelCanvas c;
  c.reset(plan);
  c.brush(40, 50, 2, 77);
  const cv::Mat before = c.codes().clone();
  cv::Mat bad(plan.size(), CV_8U, cv::Scalar(0));
  bad.at<unsigned char>(7, 11) = 100;
  cv::imwrite(tmp / "bad.png", bad);
  try {
    c.load(tmp / "bad.png");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.png"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("pixel (11, 7)"), std::string::npos) << e.what();
  }
  cv::imwrite(tmp / "small.png", cv::Mat(10, 10, CV_8U, cv::Scalar(0)));
  EXPECT_THROW(c.load(tmp / "small.png"), InputError);
  EXPECT_THROW(c.load(tmp / "missing.png"), InputError);
  EXPECT_EQ(cv::countNonZero(c.codes() != before), 0);  // unchanged
  EXPECT_EQ(c.undoDepth(), 1u);
}
