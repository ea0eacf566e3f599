#pragma once
// The topological graph of Mozos et al.: one node per region, one edge per pair of regions that share a border
// (rooms and corridors are joined through doorway nodes where the labels have them). Nodes sit at an anchor cell
// inside their region and edges carry the free path between their anchors (edge_route.h).
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

struct GraphNode {
  int id = 0;             ///< region id (value in the region image)
  int label = 0;          ///< 0 room, 1 corridor, 2 doorway
  int cells = 0;
  double area_m2 = 0;
  cv::Point2d centroid_px;  ///< pixels (x = column, y = row, row 0 at the top)
  cv::Point2d centroid_m;   ///< metres, x right, y up: origin + ((col + 0.5) res, (rows - row - 0.5) res)
  cv::Rect bbox_px;
  cv::Point anchor_px;      ///< where the node is drawn: a cell well inside the region (edge_route.h, regionAnchors)
  cv::Point2d anchor_m;     ///< the anchor cell's centre in metres (same convention as centroid_m)
  bool centroid_inside = true;  ///< false for non-convex regions (a corridor loop) whose centroid lies outside
};

struct GraphEdge {
  int a = 0, b = 0;       ///< node ids, a < b
  int border_cells = 0;   ///< 8-neighbour cell pairs along the shared border
  bool via_doorway = false;  ///< one end is a doorway node
  cv::Point2d contact_px;    ///< mean position of the border cells (pixels): where the two regions meet
  /// The edge as drawn: cells from a's anchor to b's anchor along the free path through the shared border, every
  /// straight piece on cells of the two regions (EdgeRouter::route). Empty for graphs read from files without it.
  std::vector<cv::Point> path_px;
};

struct TopologicalGraph {
  double resolution = 0.05;
  int rows = 0, cols = 0;
  std::vector<GraphNode> nodes;
  std::vector<GraphEdge> edges;
  const GraphNode* node(int id) const;
  /// Number of connected components (union-find over the edges).
  int connectedComponents() const;
};

/// `origin`: world coordinates (m) of the lower-left corner of the map (the map's x_min, y_min). `regions` may cover
/// only a part of the map: its cell (0, 0) is the map's cell `offset`, the map is `map_size` cells (empty: the size
/// of `regions`); the graph is then in the map's frame, the same graph as that of the same regions on the whole map.
TopologicalGraph buildGraph(const RegionMap& regions, double resolution, cv::Point2d origin = {0, 0},
                            cv::Point offset = {}, cv::Size map_size = {});

}  // namespace gridtopo::topology
