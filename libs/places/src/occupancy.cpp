#include "gridtopo/places/occupancy.h"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "gridtopo/core/error.h"

namespace gridtopo::places {

OccupancyImage occupancyFromGrey(const cv::Mat& image, double resolution, const std::string& source,
                                 int free_threshold, int occupied_threshold) {
  if (image.empty()) throw InputError(source, "empty image (unreadable or unknown format?)");
  if (image.depth() != CV_8U) throw InputError(source, "image is not 8-bit per channel");
  if (!std::isfinite(resolution) || resolution <= 0)
    throw InputError(source, 0, "resolution", "must be a positive number of metres per cell");
  cv::Mat grey;
  if (image.channels() == 1) grey = image;
  else if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else if (image.channels() == 4) cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
  else throw InputError(source, "unsupported number of channels");
  OccupancyImage occ;
  occ.resolution = resolution;
  occ.cells.create(grey.size(), CV_8UC1);
  for (int r = 0; r < grey.rows; ++r) {
    const unsigned char* g = grey.ptr<unsigned char>(r);
    unsigned char* o = occ.cells.ptr<unsigned char>(r);
    for (int c = 0; c < grey.cols; ++c)
      o[c] = g[c] >= free_threshold ? kFree : (g[c] <= occupied_threshold ? kOccupied : kUnknown);
  }
  return occ;
}

OccupancyImage occupancyFromMap(const MapImage& map, int free_threshold, int occupied_threshold) {
  return occupancyFromGrey(map.grey, map.resolution, map.source, free_threshold, occupied_threshold);
}

std::size_t openFreeSpace(OccupancyImage& occ, double radius) {
  if (occ.cells.empty() || !(radius > 0) || !std::isfinite(radius)) return 0;
  const int r = static_cast<int>(std::lround(radius / occ.resolution));
  if (r < 1) return 0;
  // The opening as cv::morphologyEx's MORPH_OPEN makes it (an erosion, then a dilation of its result with the same
  // kernel and border), the dilation in place and the free mask let go in between: one full-map image less at once.
  // Pixels outside the image count as free for the erosion, so a map cut at its border keeps its edge cells.
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * r + 1, 2 * r + 1));
  cv::Mat opened;
  {
    const cv::Mat free_mask = occ.cells == kFree;
    cv::erode(free_mask, opened, kernel, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(255));
  }
  cv::dilate(opened, opened, kernel, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(255));
  std::size_t removed = 0;
  for (int y = 0; y < occ.cells.rows; ++y) {
    unsigned char* c = occ.cells.ptr<unsigned char>(y);
    const unsigned char* o = opened.ptr<unsigned char>(y);
    for (int x = 0; x < occ.cells.cols; ++x)
      if (c[x] == kFree && !o[x]) c[x] = kUnknown, ++removed;
  }
  return removed;
}

std::size_t countFree(const OccupancyImage& occ) {
  std::size_t n = 0;  // counted in place: no mask image of the map
  for (int y = 0; y < occ.cells.rows; ++y) {
    const unsigned char* c = occ.cells.ptr<unsigned char>(y);
    for (int x = 0; x < occ.cells.cols; ++x) n += c[x] == kFree;
  }
  return n;
}

}  // namespace gridtopo::places
