#pragma once
// A map as the GUI shows it: a grey occupancy image (row 0 = the map's top, i.e. largest y; 255 free, 0
// occupied, 128 unknown, value = round(255 · p_free)) with its resolution and the world position of its
// lower-left corner. Built from any map the project reads (MRPT COccupancyGridMap2D) or from the SLAM's
// particle map, so every view, the topology and the label painter share one coordinate convention.
#include <mrpt/maps/COccupancyGridMap2D.h>

#include <opencv2/core.hpp>
#include <string>

#include "gridtopo/core/map_image.h"
#include "gridtopo/slam/grid_map.h"

namespace gridtopo::session {

struct MapLayer {
  cv::Mat grey;              ///< CV_8UC1
  double resolution = 0.05;  ///< m per cell
  double origin_x = 0.0;     ///< world x of the image's left edge (m)
  double origin_y = 0.0;     ///< world y of the image's bottom edge (m)
  std::string source;        ///< file it came from, or a name for display ("<slam map, N scans>")
  /// How the grey levels read as free space (topology::TopologyOptions::freeThresholdFor): set by the map reader
  /// (io::readMap) or by whoever built the map, never guessed from `source`.
  MapKind kind = MapKind::PlainImage;

  bool empty() const { return grey.empty(); }
  int rows() const { return grey.rows; }
  int cols() const { return grey.cols; }
  double width_m() const { return cols() * resolution; }
  double height_m() const { return rows() * resolution; }
  /// World coordinates of a cell centre.
  cv::Point2d cellCentre(int row, int col) const {
    return {origin_x + (col + 0.5) * resolution, origin_y + (rows() - row - 0.5) * resolution};
  }
  /// Cell (row, col) that contains a world point; false when outside the image.
  bool worldToCell(double x, double y, int& row, int& col) const;
  /// p(occupied) of a cell (1 - grey/255).
  double occupancy(int row, int col) const { return 1.0 - grey.at<unsigned char>(row, col) / 255.0; }
  /// The layer as the typed map the topology takes (the grey image shared, not copied).
  MapImage image() const { return {grey, resolution, {origin_x, origin_y}, kind, source, {}}; }
};

/// The layer of a typed map (as io::readMap returns it).
MapLayer mapLayerFromImage(const MapImage& map);

/// From an MRPT grid (as read by io::readGridMap, or built by the SLAM: MapKind::ProbabilisticGrid): the exact
/// image io::gridToImage() gives.
MapLayer mapLayerFromGrid(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& source, MapKind kind);

/// Fast conversion of the SLAM particle map for live display (a probabilistic grid): covers the allocated tiles,
/// unknown = 128.
MapLayer mapLayerFromSlam(const slam::GridMap& map);

/// A `cols` x `rows` map made of copies of `src` side by side (benchmarks: a big map with real content).
MapLayer tiledMap(const MapLayer& src, int cols, int rows);

/// The MRPT grid of a map layer (grey -> p_free), e.g. to write it with the io writers.
mrpt::maps::COccupancyGridMap2D gridFromLayer(const MapLayer& layer);

}  // namespace gridtopo::session
