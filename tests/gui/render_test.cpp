// The view transform and the rasteriser of the map view, pixel by pixel on tiny images. No display needed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <tuple>
#include <utility>

#include "gridtopo/session/render.h"
#include "test_helpers.h"

using namespace gridtopo;
using session::MapLayer;
using session::MapRaster;
using session::ViewTransform;
using guitest::pixelsOf;

namespace {
const cv::Vec3b kBackground(1, 2, 3);

cv::Mat screen(int w, int h) { return cv::Mat(h, w, CV_8UC3, cv::Scalar(kBackground)); }

/// A pixel of an anti-aliased stroke of colour c: within 40 levels of it on every channel.
::testing::AssertionResult stroke(const cv::Vec3b& p, const cv::Scalar& c) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(p[k] - c[k]) > 40) return ::testing::AssertionFailure() << p << " is not " << c;
  return ::testing::AssertionSuccess();
}

/// 3 rows x 4 cols at 0.5 m with its lower-left corner at (-1, 2); pixel (r, c) = (10r, 10c, 200).
MapLayer geometry() {
  MapLayer m;
  m.grey = cv::Mat(3, 4, CV_8U, cv::Scalar(7));
  m.resolution = 0.5;
  m.origin_x = -1.0;
  m.origin_y = 2.0;
  return m;
}
cv::Mat colours() {
  cv::Mat bgr(3, 4, CV_8UC3);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) bgr.at<cv::Vec3b>(r, c) = cv::Vec3b(10 * r, 10 * c, 200);
  return bgr;
}
}  // namespace

TEST(ViewTransform, ScreenAndWorldAreInverseWithYUp) {
  ViewTransform v;
  v.x0 = -2, v.y0 = 3, v.ppm = 10;
  EXPECT_EQ(v.toScreen(-2, 3), cv::Point2d(0, 0));
  EXPECT_EQ(v.toScreen(0, 0), cv::Point2d(20, 30));  // y up in the world, down on screen
  EXPECT_EQ(v.toWorld(20, 30), cv::Point2d(0, 0));
  const cv::Point2d w = v.toWorld(v.toScreen(1.25, -4.5).x, v.toScreen(1.25, -4.5).y);
  EXPECT_DOUBLE_EQ(w.x, 1.25);
  EXPECT_DOUBLE_EQ(w.y, -4.5);
  // Dragging the map 10 px right and 20 px down moves the world under the cursor with it.
  v.pan(10, 20);
  EXPECT_EQ(v.toScreen(0, 0), cv::Point2d(30, 50));
  EXPECT_DOUBLE_EQ(v.ppm, 10);
}

TEST(ViewTransform, ZoomKeepsThePointUnderTheCursorAndIsClamped) {
  ViewTransform v;
  v.x0 = 5, v.y0 = 5, v.ppm = 20;
  const cv::Point2d under = v.toWorld(37, 81);
  v.zoomAt(37, 81, 2.5);
  EXPECT_DOUBLE_EQ(v.ppm, 50);
  const cv::Point2d s = v.toScreen(under.x, under.y);
  EXPECT_NEAR(s.x, 37, 1e-9);
  EXPECT_NEAR(s.y, 81, 1e-9);
  v.zoomAt(0, 0, 1e9);
  EXPECT_DOUBLE_EQ(v.ppm, 1e5);
  v.zoomAt(10, 10, 1e-12);
  EXPECT_DOUBLE_EQ(v.ppm, 1e-3);
  const cv::Point2d under2 = v.toWorld(10, 10);
  v.zoomAt(10, 10, 1e-12);  // already at the bound: nothing moves
  EXPECT_NEAR(v.toWorld(10, 10).x, under2.x, 1e-6);
  EXPECT_NEAR(v.toWorld(10, 10).y, under2.y, 1e-6);
}

TEST(ViewTransform, FitCentresTheRectangleWithItsMargin) {
  ViewTransform v;
  v.fit(0, 0, 10, 5, 200, 200, 0.0);
  EXPECT_DOUBLE_EQ(v.ppm, 20);  // width limits: 200 px / 10 m
  EXPECT_DOUBLE_EQ(v.x0, 0);
  EXPECT_DOUBLE_EQ(v.y0, 7.5);
  EXPECT_EQ(v.toScreen(5, 2.5), cv::Point2d(100, 100));
  v.fit(0, 0, 10, 5, 200, 200);  // default margin 3 % on each side
  EXPECT_DOUBLE_EQ(v.ppm, 200 / (10 * 1.06));
  EXPECT_NEAR(v.toScreen(0, 2.5).x, 0.03 * 10 * v.ppm, 1e-9);
  EXPECT_NEAR(v.toScreen(5, 2.5).y, 100, 1e-9);
  v.fit(-1, -1, 1, 1, 300, 100, 0.0);  // height limits
  EXPECT_DOUBLE_EQ(v.ppm, 50);
  EXPECT_NEAR(v.toScreen(0, 0).x, 150, 1e-9);
  EXPECT_NEAR(v.toScreen(0, 0).y, 50, 1e-9);
  v.fit(0, 0, 10, 10, 0, 0);  // no window yet: a usable scale
  EXPECT_DOUBLE_EQ(v.ppm, 1);
}

TEST(MapRaster, DrawsEachCellAsASquareAtItsWorldPosition) {
  MapRaster r;
  EXPECT_TRUE(r.empty());
  r.set(colours(), geometry());
  EXPECT_FALSE(r.empty());
  EXPECT_TRUE(r.geometry().grey.empty());  // geometry only
  EXPECT_DOUBLE_EQ(r.geometry().origin_y, 2.0);
  // 20 px per metre = 10 px per cell; the map's top-left corner (-1, 3.5) at screen (5, 5).
  ViewTransform v;
  v.ppm = 20, v.x0 = -1.25, v.y0 = 3.75;
  cv::Mat s = screen(60, 45);
  r.draw(s, v);
  EXPECT_EQ(s.at<cv::Vec3b>(5, 5), cv::Vec3b(0, 0, 200));     // cell (0, 0)
  EXPECT_EQ(s.at<cv::Vec3b>(14, 14), cv::Vec3b(0, 0, 200));
  EXPECT_EQ(s.at<cv::Vec3b>(5, 15), cv::Vec3b(0, 10, 200));    // cell (0, 1)
  EXPECT_EQ(s.at<cv::Vec3b>(15, 5), cv::Vec3b(10, 0, 200));    // cell (1, 0)
  EXPECT_EQ(s.at<cv::Vec3b>(34, 44), cv::Vec3b(20, 30, 200));  // cell (2, 3), bottom-right
  // Outside the map the screen is untouched.
  EXPECT_EQ(s.at<cv::Vec3b>(4, 4), kBackground);
  EXPECT_EQ(s.at<cv::Vec3b>(5, 45), kBackground);
  EXPECT_EQ(s.at<cv::Vec3b>(35, 20), kBackground);
  int map_pixels = 0;
  for (int y = 0; y < s.rows; ++y)
    for (int x = 0; x < s.cols; ++x) map_pixels += s.at<cv::Vec3b>(y, x) != kBackground;
  EXPECT_EQ(map_pixels, 40 * 30);
}

TEST(MapRaster, ClipsToTheScreenAndSkipsMapsOutOfView) {
  MapRaster r;
  r.set(colours(), geometry());
  ViewTransform v;
  v.ppm = 20, v.x0 = -0.5, v.y0 = 3.0;  // world (-0.5, 3.0) = cell (1, 1)'s top-left at the screen origin
  cv::Mat s = screen(15, 15);
  r.draw(s, v);
  EXPECT_EQ(s.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 10, 200));
  EXPECT_EQ(s.at<cv::Vec3b>(14, 14), cv::Vec3b(20, 20, 200));
  v.x0 = 100;  // far right of the map
  cv::Mat t = screen(15, 15);
  r.draw(t, v);
  EXPECT_EQ(cv::countNonZero(t.reshape(1) != cv::Mat(screen(15, 15)).reshape(1)), 0);
  MapRaster none;
  none.set(cv::Mat(), geometry());
  EXPECT_TRUE(none.empty());
  none.draw(t, v);  // draws nothing
}

TEST(MapRaster, ZoomedOutViewsSampleAnAveragedMipLevel) {
  // 256 x 256 cells of alternating black / white columns at 0.05 m.
  cv::Mat bgr(256, 256, CV_8UC3);
  for (int c = 0; c < 256; ++c) bgr.col(c).setTo(c % 2 ? cv::Scalar(255, 255, 255) : cv::Scalar(0, 0, 0));
  MapLayer g;
  g.resolution = 0.05, g.origin_x = 0, g.origin_y = 0;
  MapRaster r;
  r.set(bgr, g);
  ViewTransform v;
  v.x0 = 0, v.y0 = 256 * 0.05;
  // One cell per pixel: level 0, the stripes are kept.
  v.ppm = 20;
  cv::Mat s = screen(256, 256);
  r.draw(s, v);
  EXPECT_EQ(s.at<cv::Vec3b>(100, 10), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(s.at<cv::Vec3b>(100, 11), cv::Vec3b(255, 255, 255));
  // Two cells per pixel: level 1, each pixel the mean of two columns.
  v.ppm = 10;
  cv::Mat z = screen(128, 128);
  r.draw(z, v);
  for (int x : {0, 10, 63, 127}) {
    const cv::Vec3b p = z.at<cv::Vec3b>(60, x);
    EXPECT_NEAR(p[0], 127.5, 1) << x;
    EXPECT_EQ(p[0], p[2]);
  }
}

TEST(Render, GreyToBgrAndLabelColours) {
  const cv::Mat grey = (cv::Mat_<unsigned char>(1, 3) << 0, 128, 255);
  const cv::Mat bgr = session::greyToBgr(grey);
  ASSERT_EQ(bgr.type(), CV_8UC3);
  EXPECT_EQ(bgr.at<cv::Vec3b>(0, 1), cv::Vec3b(128, 128, 128));
  EXPECT_EQ(bgr.at<cv::Vec3b>(0, 2), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(session::labelColour(0), cv::Scalar(220, 120, 40));  // room: blue
  EXPECT_EQ(session::labelColour(1), cv::Scalar(60, 190, 60));   // corridor: green
  EXPECT_EQ(session::labelColour(2), cv::Scalar(40, 40, 230));   // doorway: red
  EXPECT_EQ(session::labelColour(3), cv::Scalar(128, 128, 128));
  EXPECT_EQ(session::labelColour(-1), cv::Scalar(128, 128, 128));
}

TEST(Render, LabelOverlayBlendsWithAlphaFromConfidence) {
  const cv::Mat grey = (cv::Mat_<unsigned char>(1, 5) << 100, 200, 100, 100, 50);
  const cv::Mat labels = (cv::Mat_<unsigned char>(1, 5) << 0, 2, 1, 255, 3);
  // Without confidence: alpha 0.6.
  cv::Mat o = session::labelOverlay(grey, labels);
  EXPECT_EQ(o.at<cv::Vec3b>(0, 0), cv::Vec3b(172, 112, 64));   // 0.4 * 100 + 0.6 * (220, 120, 40)
  EXPECT_EQ(o.at<cv::Vec3b>(0, 1), cv::Vec3b(104, 104, 218));  // 0.4 * 200 + 0.6 * (40, 40, 230)
  EXPECT_EQ(o.at<cv::Vec3b>(0, 2), cv::Vec3b(76, 154, 76));    // 0.4 * 100 + 0.6 * (60, 190, 60)
  EXPECT_EQ(o.at<cv::Vec3b>(0, 3), cv::Vec3b(100, 100, 100));  // no label: grey
  EXPECT_EQ(o.at<cv::Vec3b>(0, 4), cv::Vec3b(50, 50, 50));
  // Confidence: alpha = 0.25 + 0.5 * clamp(confidence, 0, 1).
  const cv::Mat conf = (cv::Mat_<float>(1, 5) << 1.0f, 0.0f, 2.0f, 1.0f, 1.0f);
  o = session::labelOverlay(grey, labels, conf);
  EXPECT_EQ(o.at<cv::Vec3b>(0, 0), cv::Vec3b(190, 115, 55));   // alpha 0.75
  EXPECT_EQ(o.at<cv::Vec3b>(0, 1), cv::Vec3b(160, 160, 208));  // alpha 0.25 (rounded half away from zero)
  EXPECT_EQ(o.at<cv::Vec3b>(0, 2), cv::Vec3b(70, 168, 70));    // confidence 2 counts as 1
  EXPECT_EQ(o.at<cv::Vec3b>(0, 3), cv::Vec3b(100, 100, 100));
}

TEST(Render, CodesOverlayReadsTheTrainingCodes) {
  const cv::Mat grey(1, 5, CV_8U, cv::Scalar(100));
  const cv::Mat codes = (cv::Mat_<unsigned char>(1, 5) << 77, 115, 179, 0, 78);
  const cv::Mat labels = (cv::Mat_<unsigned char>(1, 5) << 0, 1, 2, 255, 255);
  const cv::Mat a = session::codesOverlay(grey, codes), b = session::labelOverlay(grey, labels);
  EXPECT_EQ(cv::countNonZero(a.reshape(1) != b.reshape(1)), 0);
  EXPECT_EQ(a.at<cv::Vec3b>(0, 3), cv::Vec3b(100, 100, 100));
  EXPECT_EQ(a.at<cv::Vec3b>(0, 4), cv::Vec3b(100, 100, 100));
}

TEST(Render, ScaleBarIsARoundLengthAboutASixthOfTheWidth) {
  // 600 px at 20 px/m: a sixth is 5 m, drawn 100 px long from x = 12 on row rows - 14.
  // The first run of black pixels on the bar's row (the label follows after a gap).
  auto barPixels = [](const cv::Mat& s) {
    int first = -1, last = -1;
    const int y = s.rows - 14;
    for (int x = 0; x < s.cols; ++x) {
      const bool black = s.at<cv::Vec3b>(y, x) == cv::Vec3b(0, 0, 0);
      if (black && first < 0) first = x;
      if (black) last = x;
      if (!black && first >= 0) break;
    }
    return std::make_pair(first, last);
  };
  ViewTransform v;
  v.ppm = 20;
  cv::Mat s = screen(600, 400);
  session::drawScaleBar(s, v);
  auto [first, last] = barPixels(s);
  EXPECT_NEAR(first, 12, 2);
  EXPECT_NEAR(last, 112, 2);
  EXPECT_EQ(s.at<cv::Vec3b>(400 - 30, 8), cv::Vec3b(255, 255, 255));  // the white box behind it
  EXPECT_EQ(s.at<cv::Vec3b>(400 - 40, 8), kBackground);
  EXPECT_EQ(s.at<cv::Vec3b>(400 - 14, 3), kBackground);
  // 7 m would be a sixth of 840 px: rounded down to 5 m (1, 2, 5 x 10^k).
  v.ppm = 20;
  cv::Mat w = screen(840, 100);
  session::drawScaleBar(w, v);
  std::tie(first, last) = barPixels(w);
  EXPECT_NEAR(first, 12, 2);
  EXPECT_NEAR(last, 112, 2);
  // 0.0667 m -> 5 cm = 75 px at 1500 px/m.
  v.ppm = 1500;
  cv::Mat c = screen(600, 100);
  session::drawScaleBar(c, v);
  std::tie(first, last) = barPixels(c);
  EXPECT_NEAR(first, 12, 2);
  EXPECT_NEAR(last, 87, 2);
}

TEST(Render, PathAndPoseAreDrawnAtTheirScreenPositions) {
  ViewTransform v;
  v.x0 = 0, v.y0 = 5, v.ppm = 10;
  const cv::Scalar red(0, 0, 255);
  cv::Mat s = screen(60, 60);
  session::drawPath(s, v, {{1, 1}}, red);  // one point: nothing
  EXPECT_EQ(cv::countNonZero(s.reshape(1) != cv::Mat(screen(60, 60)).reshape(1)), 0);
  session::drawPath(s, v, {{1, 1}, {3, 1}, {3, 3}}, red);  // screen (10, 40) -> (30, 40) -> (30, 20)
  EXPECT_TRUE(stroke(s.at<cv::Vec3b>(40, 20), red));
  EXPECT_TRUE(stroke(s.at<cv::Vec3b>(30, 30), red));
  EXPECT_EQ(s.at<cv::Vec3b>(45, 20), kBackground);
  EXPECT_EQ(s.at<cv::Vec3b>(30, 40), kBackground);

  const cv::Scalar green(0, 255, 0);
  cv::Mat p = screen(60, 60);
  session::drawPose(p, v, 2, 2, 0, green);  // screen (20, 30), heading +x
  EXPECT_EQ(p.at<cv::Vec3b>(30, 20), cv::Vec3b(0, 255, 0));
  EXPECT_TRUE(stroke(p.at<cv::Vec3b>(30, 26), green));  // tick to (27, 30)
  EXPECT_EQ(p.at<cv::Vec3b>(30, 14), kBackground);           // nothing behind
  cv::Mat q = screen(60, 60);
  session::drawPose(q, v, 2, 2, M_PI / 2, green, 5);  // heading +y = up on screen, tick to (20, 21)
  EXPECT_TRUE(stroke(q.at<cv::Vec3b>(22, 20), green));
  EXPECT_EQ(q.at<cv::Vec3b>(38, 20), kBackground);
  // Far off screen: nothing drawn.
  cv::Mat off = screen(60, 60);
  session::drawPose(off, v, 100, 100, 0, green);
  EXPECT_EQ(cv::countNonZero(off.reshape(1) != cv::Mat(screen(60, 60)).reshape(1)), 0);
}

TEST(Render, ClosureIsALineWithDotsDashedWhenRejected) {
  ViewTransform v;
  v.x0 = 0, v.y0 = 5, v.ppm = 10;
  cv::Mat s = screen(80, 60);
  session::drawClosure(s, v, {1, 1}, {6, 1}, false);  // screen (10, 40) -> (60, 40)
  // Solid: every pixel along the line, exactly the closure colour (no anti-aliasing), and a dot at each end.
  for (int x = 10; x <= 60; ++x) EXPECT_EQ(s.at<cv::Vec3b>(40, x), cv::Vec3b(255, 0, 255)) << x;
  EXPECT_EQ(s.at<cv::Vec3b>(37, 10), cv::Vec3b(255, 0, 255));  // the dot reaches 3 px above the end
  EXPECT_EQ(s.at<cv::Vec3b>(37, 35), kBackground);             // the line itself is 2 px wide
  EXPECT_EQ(s.at<cv::Vec3b>(30, 35), kBackground);
  EXPECT_EQ(pixelsOf(s, session::kRejectedClosureColour), 0);

  cv::Mat r = screen(80, 60);
  session::drawClosure(r, v, {1, 1}, {6, 1}, true);
  EXPECT_EQ(pixelsOf(r, session::kClosureColour), 0);
  int on = 0, gaps = 0;
  for (int x = 14; x <= 56; ++x) {  // between the dots
    const bool drawn = r.at<cv::Vec3b>(40, x) == cv::Vec3b(170, 170, 170);
    on += drawn;
    gaps += !drawn && r.at<cv::Vec3b>(40, x - 1) == cv::Vec3b(170, 170, 170);
  }
  EXPECT_GT(on, 20);
  EXPECT_GE(gaps, 3);  // dashed: the line breaks several times
  EXPECT_LT(pixelsOf(r, session::kRejectedClosureColour), pixelsOf(s, session::kClosureColour));

  // Ends far off screen: the part in view only (clipped), no dots; wholly out of view: nothing.
  cv::Mat far = screen(80, 60);
  session::drawClosure(far, v, {-1e7, 1}, {1e7, 1}, true);
  EXPECT_GT(pixelsOf(far, session::kRejectedClosureColour), 40);
  cv::Mat off = screen(80, 60);
  session::drawClosure(off, v, {100, 100}, {200, 100}, false);
  EXPECT_EQ(pixelsOf(off, session::kClosureColour), 0);

  // A global closure: the same solid line, in its own colour.
  cv::Mat g = screen(80, 60);
  session::drawClosure(g, v, {1, 1}, {6, 1}, false, true);
  EXPECT_EQ(pixelsOf(g, session::kClosureColour), 0);
  EXPECT_EQ(pixelsOf(g, session::kGlobalClosureColour), pixelsOf(s, session::kClosureColour));
  EXPECT_EQ(g.at<cv::Vec3b>(40, 35), cv::Vec3b(0, 140, 255));
}
