#pragma once
// The input of place labelling: a plain occupancy image (free / occupied / unknown) with its resolution.
// Kept independent of any map file format; apps convert what they read into this.
#include <opencv2/core.hpp>

#include <string>

#include "gridtopo/core/map_image.h"

namespace gridtopo::places {

/// Cell states stored in OccupancyImage::cells. kSeen: free in the map, but no place (the topology's map
/// preparation, topology/map_preparation.h: free space the laser saw that no robot stood in); it takes no label,
/// and simulated beams pass through it as through free cells (the features describe the space the laser saw).
enum CellState : unsigned char { kOccupied = 0, kUnknown = 128, kSeen = 192, kFree = 255 };

struct OccupancyImage {
  cv::Mat cells;            ///< CV_8UC1, one of CellState; row 0 is the top of the map image
  double resolution = 0.05; ///< metres per cell

  int rows() const { return cells.rows; }
  int cols() const { return cells.cols; }
  bool isFree(int r, int c) const { return cells.at<unsigned char>(r, c) == kFree; }
};

/// Classifies a grey image (CV_8U, 1, 3 or 4 channels; colour is converted to grey): grey >= free_threshold is
/// free, grey <= occupied_threshold is occupied, anything in between unknown. Throws gridtopo::InputError
/// (naming `source`) for an empty image, a non-8-bit image, or a non-positive / non-finite resolution.
OccupancyImage occupancyFromGrey(const cv::Mat& image, double resolution, const std::string& source = "<image>",
                                 int free_threshold = 250, int occupied_threshold = 50);

/// occupancyFromGrey of a typed map's grey image and resolution (errors name `map.source`). The threshold is the
/// caller's choice for the map's kind (topology::TopologyOptions::freeThresholdFor(map.kind)).
OccupancyImage occupancyFromMap(const MapImage& map, int free_threshold, int occupied_threshold = 50);

/// Morphological opening of the free space (OpenCV erode then dilate, square kernel of half-side `radius` metres,
/// rounded to whole cells; < half a cell does nothing): free passages narrower than about 2 * radius + 1 cell and
/// free specks and streaks that thin disappear. Made for occupancy grids built by SLAM, where walls seen edge-on
/// or through glass come out as dotted lines (one-cell gaps that rays and regions leak through) and single rays
/// through windows leave one-cell free streaks in the unknown. Cells that stop being free become kUnknown.
/// Returns the number of cells removed.
std::size_t openFreeSpace(OccupancyImage& occ, double radius);

/// Number of free cells.
std::size_t countFree(const OccupancyImage& occ);

}  // namespace gridtopo::places
