#pragma once
// A map as the topology sees it, with its kind: the grey image, the resolution, the world position and what the map
// is (a drawn plan, a ROS map, a probabilistic grid the SLAM built), as one value. The map readers return it
// (io::readMap), whoever builds a map sets its kind, and the free-space thresholds are picked from the kind
// (topology::TopologyOptions::freeThresholdFor), never from a file name.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace gridtopo {

/// What a map is, which decides how its grey levels are read as free space
/// (topology::TopologyOptions::freeThresholdFor / freeOpeningRadiusFor): a plain image (a drawn plan), a ROS
/// map_server map (0 / 205 / 254 greys), or an MRPT probabilistic grid (a .gridmap(.gz) file or a map the SLAM
/// built, whose clamped log-odds never reach grey 250).
enum class MapKind { PlainImage, RosMap, ProbabilisticGrid };

struct MapImage {
  cv::Mat grey;              ///< CV_8UC1, 255 = free, 0 = occupied (round(255 p_free)); row 0 is the map's top
  double resolution = 0.05;  ///< metres per cell
  cv::Point2d origin{0, 0};  ///< world (x_min, y_min): the lower-left corner of the image, metres
  MapKind kind = MapKind::PlainImage;
  std::string source;  ///< where it came from (a path, "<slam map, N scans>"), for messages only
  /// Where the robot was while the map was built (world x, y in metres), in time order; empty when unknown (a
  /// plan, a map file read alone). The topology's map preparation weighs it (topology/map_preparation.h).
  std::vector<cv::Point2d> path;
};

}  // namespace gridtopo
