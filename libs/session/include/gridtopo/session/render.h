#pragma once
// The map view as an image: a view transform (world <-> screen pixels) and a rasteriser that draws the map and
// every overlay into a BGR cv::Mat of the window's size. The wx canvas only blits this image, so the exported
// PNG, the screenshot and the unit tests see exactly what the user sees. Only the visible part of the map is
// sampled (cv::warpAffine on the screen buffer, from a mip level of the map), so the cost of a frame depends on
// the window size, not on the map size.
#include <opencv2/core.hpp>
#include <vector>

#include "gridtopo/session/map_layer.h"

namespace gridtopo::session {

/// screen = ((x - x0) · ppm, (y0 - y) · ppm): (x0, y0) is the world point at the top-left screen corner.
struct ViewTransform {
  double x0 = 0.0, y0 = 0.0;
  double ppm = 20.0;  ///< screen pixels per metre

  cv::Point2d toScreen(double x, double y) const { return {(x - x0) * ppm, (y0 - y) * ppm}; }
  cv::Point2d toWorld(double sx, double sy) const { return {x0 + sx / ppm, y0 - sy / ppm}; }
  /// Zoom by `factor` keeping the world point under screen (sx, sy) fixed.
  void zoomAt(double sx, double sy, double factor);
  void pan(double dsx, double dsy) { x0 -= dsx / ppm, y0 += dsy / ppm; }
  /// Fits a world rectangle into a w × h window with a margin.
  void fit(double xmin, double ymin, double xmax, double ymax, int w, int h, double margin = 0.03);
};

/// A map raster (BGR) with mip levels for zoomed-out views.
class MapRaster {
 public:
  MapRaster() = default;
  /// `bgr` is aligned with `geometry` (same rows/cols); geometry.grey is not used.
  void set(const cv::Mat& bgr, const MapLayer& geometry);
  bool empty() const { return levels_.empty(); }
  /// Draws the raster into `screen` (BGR, already cleared).
  void draw(cv::Mat& screen, const ViewTransform& v) const;
  const MapLayer& geometry() const { return geo_; }

 private:
  std::vector<cv::Mat> levels_;  // level k: 2^k cells per pixel (INTER_AREA)
  MapLayer geo_;
};

/// Grey map -> BGR.
cv::Mat greyToBgr(const cv::Mat& grey);
/// Blends label colours (room blue, corridor green, doorway red; as topology::renderOverlay) onto a grey map.
/// `confidence` (CV_32F, per cell, optional) shades the colour: alpha = 0.25 + 0.5 · confidence.
cv::Mat labelOverlay(const cv::Mat& grey, const cv::Mat& labels, const cv::Mat& confidence = cv::Mat());
/// Same for training codes (77/115/179/0) of the label painter.
cv::Mat codesOverlay(const cv::Mat& grey, const cv::Mat& codes);
cv::Scalar labelColour(int label);  ///< BGR

/// Draws a scale bar (a round length about 1/6 of the width) at the bottom-left.
void drawScaleBar(cv::Mat& screen, const ViewTransform& v);
/// Polyline of world points.
void drawPath(cv::Mat& screen, const ViewTransform& v, const std::vector<cv::Point2d>& pts, const cv::Scalar& c,
              int thickness = 1);
/// A robot pose: a circle of radius r pixels with a heading tick.
void drawPose(cv::Mat& screen, const ViewTransform& v, double x, double y, double theta, const cv::Scalar& c,
              int r = 3);

/// The colours of the loop closure's edges (BGR): accepted closures magenta, global ones (found beyond the drift
/// window by the place signatures) orange, those the optimisation rejected grey.
inline const cv::Scalar kClosureColour(255, 0, 255);
inline const cv::Scalar kGlobalClosureColour(0, 140, 255);
inline const cv::Scalar kRejectedClosureColour(170, 170, 170);
/// A loop-closure edge between world points `a` (the older submap) and `b` (the scan that closed the loop): a 2 px
/// line with a dot at each end, in kClosureColour (kGlobalClosureColour when `global`); dashed in
/// kRejectedClosureColour when `rejected`. Drawn without anti-aliasing, so its pixels have exactly that colour (tests
/// count them).
void drawClosure(cv::Mat& screen, const ViewTransform& v, const cv::Point2d& a, const cv::Point2d& b, bool rejected,
                 bool global = false);

}  // namespace gridtopo::session
