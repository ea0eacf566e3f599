#pragma once
// Hand-made occupancy images for the places tests.
#include <cmath>

#include "gridtopo/places/occupancy.h"

namespace gridtopo::places::test {

/// A free rectangle of w x h metres inside 1-cell walls, centred in an image with a margin.
inline OccupancyImage rectangleRoom(double w, double h, double res) {
  const int cw = static_cast<int>(std::lround(w / res)), ch = static_cast<int>(std::lround(h / res));
  OccupancyImage occ;
  occ.resolution = res;
  occ.cells = cv::Mat(ch + 10, cw + 10, CV_8U, cv::Scalar(kOccupied));
  occ.cells(cv::Rect(5, 5, cw, ch)).setTo(kFree);
  return occ;
}

}  // namespace gridtopo::places::test
