#pragma once
// A laser scan turned once per filter step into what every particle needs: beams to insert into the map
// (robot frame, hit or free-only) and the subset of end points used for matching.
#include <vector>

#include "gridtopo/io/scan_record.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/pose2.h"

namespace gridtopo::slam {

struct BeamOptions {
  /// Returns at or beyond this range (m) are not used as obstacles: free space is marked up to it and the
  /// beam is not matched. 0 = the sensor's max_range.
  double max_usable_range = 30.0;
  double min_range = 0.05;  ///< returns closer than this (m) are ignored
  /// REP-117: a "no return" reading (+inf or >= max_range) clears free space up to no_return_range;
  /// NaN / zero / negative readings carry no information and are ignored.
  bool clear_no_return = true;
  double no_return_range = 5.0;  ///< m
  /// Use every n-th hit beam for matching (all beams are inserted). 0 = from matching_beam_angle: the step that
  /// spaces the matching beams about that angle apart (2 for a 1° laser, 4 for a 0.5° one), so that the cost of a
  /// step and the scale of the likelihood do not depend on the laser's angular resolution.
  int matching_beam_step = 2;
  double matching_beam_angle = 0.0349066;  ///< rad (2°), for matching_beam_step = 0
};

struct PreparedScan {
  Pose2 sensor;                     ///< laser pose in the robot frame
  std::vector<MapBeam> map_beams;   ///< in the robot frame
  /// Matching end points in the robot frame, and the same points moved one cell back along the beam
  /// (the cell in front of an obstacle must be free: GMapping's test against matching a wall from behind).
  std::vector<double> ex, ey, fx, fy;
  std::size_t size() const { return ex.size(); }
};

PreparedScan prepareScan(const io::LaserScan& scan, const BeamOptions& o, double resolution);

}  // namespace gridtopo::slam
