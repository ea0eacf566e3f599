#pragma once
// Where the graph is drawn (issue 15, item 4): every node at a cell well inside its region, every edge along the
// free path between its two nodes, through their shared border, never across a wall.
//  - anchor: among the region's cells at least half as far from the region's border as its deepest cell, the one
//    nearest the region's centroid (the centroid itself for a compact region; never a cell of a wall or of another
//    region, even for an L-shaped corridor or a region in two parts).
//  - route: the least-cost path from each anchor through its own region's cells (8-connected steps, each weighted
//    by 1 + (0.7 m / clearance)^2, clearance = distance to the nearest cell outside every region: paths keep to the
//    middle line of corridors and doors, and the edges of one node share that line like the lines of a metro map),
//    joined at the border cell pair of the two regions that minimises the sum of the two costs, then simplified
//    (Douglas-Peucker, 1 cell) keeping every straight piece on cells of the two regions.
#include <opencv2/core.hpp>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

/// Least-cost paths that keep to the middle of corridors and doors (the edge routes, correction rule R4): an
/// 8-connected step into a cell costs 1 + (kPathClearanceScale / clearance)^2 (times sqrt(2) diagonally), clearance
/// in metres to the nearest cell without a place.
inline constexpr double kPathClearanceScale = 0.7;

/// The anchor cell of every region (index id - 1), in the frame of `regions`. When `regions` covers a part of a map
/// whose cell (0, 0) is the map's cell `offset`, `centroids` (index id - 1) are the regions' centroids in the map's
/// frame: the anchors are then those of the same regions on the whole map (minus `offset`).
std::vector<cv::Point> regionAnchors(const RegionMap& regions, cv::Point offset = {},
                                     const std::vector<cv::Point2d>* centroids = nullptr);

struct EdgeRouter {
  /// Least-cost trees from every region's anchor inside its region.
  EdgeRouter(const RegionMap& regions, const std::vector<cv::Point>& anchors, double resolution);
  /// The polyline (cells) from anchors[a - 1] to anchors[b - 1] for two regions that share a border; empty when
  /// they share none or one anchor does not reach the border (a region in several parts).
  std::vector<cv::Point> route(int a, int b) const;

 private:
  const RegionMap& rm_;
  /// The images below cover the box of every region's cell (a cell outside it is in no region, so nothing
  /// changes: the clearance's nearest non-region cell is never further than the empty frame around the box);
  /// box_.tl() is their (0, 0) in the id image. On the hospital's map the box is 57 % of the image.
  cv::Rect box_;
  cv::Mat parent_;  ///< CV_8U direction (0..7, edge_route.cpp kDx / kDy) to the previous cell; 8: anchor, unreached
  /// (a, b), a < b -> (total cost, cell in a, cell in b) of the cheapest border cell pair (id image coordinates)
  std::map<std::pair<int, int>, std::tuple<double, cv::Point, cv::Point>> joins_;
};

}  // namespace gridtopo::topology
