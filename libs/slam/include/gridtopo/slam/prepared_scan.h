#pragma once
// A laser scan turned once per filter step into what every particle needs: beams to insert into the map
// (robot frame, hit or free-only) and the subset of end points used for matching.
#include <vector>

#include "gridtopo/core/scan_record.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/pose2.h"

namespace gridtopo::slam {

struct BeamOptions {
  /// Returns at or beyond this range (m) are not used as obstacles: free space is marked up to it and the
  /// beam is not matched. 0 = the sensor's max_range. 60 m: a long-range laser's far walls hold the heading
  /// outdoors (the drifting campus log: 40.6 m with 30, 0.27 m with 60, the filter alone; doc/slam.md).
  double max_usable_range = 60.0;
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
  /// Hits within this distance (m) of the usable range (the smaller of max_usable_range and the sensor's max
  /// range) are inserted but not matched. The previous scans mapped the walls only up to that range from poses a
  /// step behind, so beams ending near it fall past the mapped frontier at the true pose and onto mapped walls
  /// at poses behind it: along a corridor they pull every match backwards. 0 = match every hit.
  double matching_range_margin = 0.0;
  /// Hits whose beam meets the surface (its normal estimated from the neighbouring beams) at less than this angle
  /// (rad) are inserted but not matched. Along a wall seen at a grazing angle consecutive scans' end points lie
  /// metres apart, so the wall's cells there hold few hit means with gaps wider than the correspondence window:
  /// such a beam finds its correspondence only where an earlier scan's beam ended, which favours the poses that
  /// repeat an earlier scan's geometry (zero motion along a corridor). 0 = match them all.
  double matching_min_incidence = 0.0;
  /// A hit does not clear the cells of its beam that lie within this distance (m) of the surface it hit, i.e. the
  /// last surface_clearance / sin(incidence) metres of the beam (the surface's normal estimated from the
  /// neighbouring beams; hits without one clear up to their end). A beam meeting a wall at 5 degrees otherwise runs
  /// through the wall's row of cells for the last 0.6 m and wears away the wall that earlier scans mapped there.
  /// 0 = clear every cell up to the hit.
  double surface_clearance = 0.0;
};

struct PreparedScan {
  Pose2 sensor;                     ///< laser pose in the robot frame
  std::vector<MapBeam> map_beams;   ///< in the robot frame
  /// Matching end points in the robot frame, and the same points moved one cell back along the beam
  /// (the cell in front of an obstacle must be free: GMapping's test against matching a wall from behind).
  std::vector<double> ex, ey, fx, fy;
  /// Unit normal (robot frame) of the surface at each matching end point, from a line fitted to the end points of
  /// the neighbouring beams (see kNormalSpan); (0, 0) where they do not lie on one line (corners, clutter,
  /// isolated returns).
  std::vector<double> nx, ny;
  std::size_t size() const { return ex.size(); }
};

/// The surface normal at an end point comes from the end points of the beams k ± w around it, w from 2 up to this
/// cap, the first w whose outermost hits are kNormalSpan (m) apart.
constexpr int kNormalMaxNeighbours = 12;
constexpr double kNormalSpan = 0.2;
/// The neighbours' RMS distance to the fitted line (m) up to which they count as one surface.
constexpr double kNormalMaxRms = 0.02;

PreparedScan prepareScan(const LaserScan& scan, const BeamOptions& o, double resolution);

/// Every step-th matching end point of `scan` (with its free-cell point and normal), from the first; the map beams
/// and the sensor pose are not copied (a scan for scoring only: the coarse-to-fine search's coarse levels).
PreparedScan everyNthMatchingPoint(const PreparedScan& scan, std::size_t step);

}  // namespace gridtopo::slam
