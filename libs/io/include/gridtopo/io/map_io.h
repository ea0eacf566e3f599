#pragma once
// Occupancy grid maps in and out: PNG, ROS map_server PGM + YAML, MRPT .gridmap(.gz), and .simplemap.
// The exchange type is MRPT's COccupancyGridMap2D, so any MRPT program can use what gridtopo reads or builds.
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimpleMap.h>

#include <opencv2/core.hpp>
#include <string>

#include "gridtopo/core/map_image.h"

namespace gridtopo::io {

struct MapReadOptions {
  double resolution = 0.05;  ///< metres per pixel, for plain images without a YAML file
  double origin_x = 0.0;     ///< world x of the image's lower-left corner, for plain images
  double origin_y = 0.0;     ///< world y of the image's lower-left corner, for plain images
  /// The largest image (width x height cells) read: a larger one is refused from its header (PNG, PGM/PNM)
  /// before any pixel is allocated. 10^8 cells: a 500 m x 500 m map at 5 cm.
  std::size_t max_cells = 100'000'000;
};

/// Reads .png/.pgm/.jpg (with a ROS .yaml beside it if there is one), a ROS .yaml, or .gridmap / .gridmap.gz.
/// Plain images: cell p_free = grey / 255. ROS maps: map_server semantics (negate, thresholds, trinary /
/// scale / raw modes): occupied -> p_free 0, free -> 1, unknown -> 0.5. The origin and resolution are kept
/// exactly (as floats, MRPT's cell geometry type), even when the origin is not a whole number of cells.
/// Throws gridtopo::InputError naming the file (and YAML key) on bad input.
mrpt::maps::COccupancyGridMap2D::Ptr readGridMap(const std::string& path, const MapReadOptions& options = {});

/// The kind of the map file `path` as readGridMap reads it (extension case-insensitive): a probabilistic grid
/// (.gridmap, .gridmap.gz), a ROS map (.yaml / .yml, or an image with a .yaml / .yml of the same stem beside it),
/// or a plain image. The reader's own decision (readMap sets MapImage::kind from it); nothing else asks a name.
MapKind mapFileKind(const std::string& path);

/// The map of `grid` as a typed map: gridToImage, the grid's resolution and (x_min, y_min), `kind` and `source`.
MapImage mapImageOfGrid(const mrpt::maps::COccupancyGridMap2D& grid, MapKind kind, const std::string& source);

/// Reads a map file as readGridMap does and returns it typed: grey image, resolution, origin, and the kind the
/// file's format gives (a .gridmap(.gz) is a probabilistic grid, a map with a ROS .yaml a ROS map, any other image
/// a plain image); `source` = `path`.
MapImage readMap(const std::string& path, const MapReadOptions& options = {});

/// Grey image of a grid (CV_8UC1, 255 = free, 0 = occupied, value = round(255 * p_free)); row 0 is the
/// map's top (largest y), so it has the size and orientation of the image the map was read from.
cv::Mat gridToImage(const mrpt::maps::COccupancyGridMap2D& grid);

// Writers; each writes atomically (temporary file + rename).
void writeMapPng(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& path);
/// Writes `<stem>.pgm` and `<stem>.yaml` (map_server: resolution, origin, negate, occupied/free thresholds).
void writeRosMap(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& stem);
void writeGridmapGz(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& path);
/// CSimpleMap (poses + sensory frames) serialised and gzip-compressed, as MRPT's CSimpleMap::saveToFile does.
void writeSimplemap(const mrpt::maps::CSimpleMap& map, const std::string& path);
/// Picks the writer from the name: .png/.bmp/.jpg -> image, .yaml/.pgm -> ROS map (same stem),
/// .gridmap/.gridmap.gz -> MRPT serialisation (gzip). Throws std::invalid_argument for other names.
void writeGridMap(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& path);

}  // namespace gridtopo::io
