#pragma once
// Regions of Mozos et al.: 8-connected cells with the same place label.
#include <map>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

namespace gridtopo::topology {

struct Region {
  int id = 0;                ///< 1-based, the value in RegionMap::ids
  int label = 0;             ///< places::PlaceLabel as int
  int cells = 0;
  double area_m2 = 0;
  cv::Point2d centroid;      ///< pixels (x = column, y = row)
  cv::Rect bbox;             ///< pixels
};

struct RegionMap {
  cv::Mat ids;                  ///< CV_32S, 0 = no region (not free / unlabelled), else Region::id
  std::vector<Region> regions;  ///< regions[id - 1]
  const Region& region(int id) const { return regions[static_cast<std::size_t>(id - 1)]; }
};

/// `labels`: CV_8U, 0..2 = place label, anything else = no label. 8-connectivity.
RegionMap extractRegions(const cv::Mat& labels, double resolution);

/// Border length between regions: number of 8-neighbour cell pairs (each unordered pair once) whose cells belong
/// to regions a < b. Keys (a, b) with a < b. `ids` CV_32S (or CV_16U).
std::map<std::pair<int, int>, int> regionAdjacency(const cv::Mat& ids);

}  // namespace gridtopo::topology
