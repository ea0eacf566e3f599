#pragma once
// Buildings drawn as label images on a 5 cm grid, and robot paths through them given in metres: the fixtures of the
// tests of the trajectory's evidence in the topology (open spaces, thoroughfares).
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace gridtopo::test::drawn {

constexpr double kRes = 0.05;

/// Metres to cells.
inline int ci(double m) { return static_cast<int>(std::lround(m / kRes)); }

/// Sets the cells of the box [x0, x1) × [y0, y1) (metres) to `label`.
inline void box(cv::Mat& labels, double x0, double y0, double x1, double y1, unsigned char label) {
  labels(cv::Rect(cv::Point(ci(x0), ci(y0)), cv::Point(ci(x1), ci(y1)))).setTo(label);
}

/// A polyline (metres) as a trajectory in cells: a pose every 0.1 m.
inline std::vector<cv::Point2d> poses(const std::vector<cv::Point2d>& corners_m) {
  std::vector<cv::Point2d> out{corners_m.front() / kRes};
  for (std::size_t i = 1; i < corners_m.size(); ++i) {
    const cv::Point2d d = corners_m[i] - corners_m[i - 1];
    const int n = std::max(1, static_cast<int>(std::ceil(cv::norm(d) / 0.1)));
    for (int k = 1; k <= n; ++k) out.push_back((corners_m[i - 1] + d * (double(k) / n)) / kRes);
  }
  return out;
}

}  // namespace gridtopo::test::drawn
