#pragma once
// From the particle map to MRPT's COccupancyGridMap2D (the exchange type of the map writers) and to pictures
// with the trajectory drawn.
#include <mrpt/maps/COccupancyGridMap2D.h>

#include <opencv2/core.hpp>
#include <vector>

#include "gridtopo/slam/pose2.h"

#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/slam_result.h"  // ClosureLine

namespace gridtopo::slam {

/// The grid as an MRPT occupancy map covering the observed cells (plus a one-cell margin); unknown cells 0.5.
mrpt::maps::COccupancyGridMap2D toOccupancyGrid(const GridMap& map);

/// BGR picture of an occupancy grid (free white, occupied black, unknown grey) with `trajectory` drawn in red
/// (and its start in green). Row 0 is the top of the map (largest y).
/// The map (grey), the trajectory (red, its start a green dot) and the accepted loop closures (windowed ones thin
/// magenta lines, global ones thick orange lines with a ring at the query's end, on top).
cv::Mat renderMap(const mrpt::maps::COccupancyGridMap2D& grid, const std::vector<TimedPose>& trajectory = {},
                  const std::vector<ClosureLine>& closures = {});

}  // namespace gridtopo::slam
