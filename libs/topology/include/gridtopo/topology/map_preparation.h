#pragma once
// Map preparation, the topology's first stage: which free cells of a map are places. A SLAM map holds free space
// that no robot stood in: cells crossed by a few beams through a door, a window or glass, fans of rays beyond
// them, the far ends of rooms seen from the corridor. The place classifier was trained on drawn plans, where every
// free pixel is floor; given such cells it makes rooms of them. The stage weighs, in order (each a named step):
//   1. robotFits: a place is a cell that a disc of the robot's radius lying wholly in free space covers (the
//      morphological opening of the free space by that disc: thin wedges, ray streaks and the frayed edges of fans
//      are not places);
//   2. seenFromNear (when the robot's path is known): a place was seen, along a free line of sight, from a pose of
//      the path at most view_range away (the far ends of fans through windows and glass are not places);
//   3. reachable: places form connected groups; a group the path does not enter (when the path is known) or
//      smaller than min_area (always) is no place (islands of free space behind glass, beyond a window).
// Cells that are free but no place stay in the map: they take no label and no node, and the overlay and the GUI
// draw them apart. The place classifier's simulated beams pass through them as through free cells: the features of
// a place describe the space as the laser saw it (on the Intel SLAM maps of seeds 1-3, beams stopped at them broke
// the corridor loops on two seeds; passing, every seed keeps both and attaches more rooms, doc/topology.md).
// Anchored on ROSE / ROSE^2 (Kucner et al. ICRA 2021; Luperto et al. RA-L 2022), which clean partial, cluttered
// SLAM maps before segmenting them; the evidence weighed here is our own (robot clearance, visibility, reachability).
#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

#include "gridtopo/places/occupancy.h"

namespace gridtopo::topology {

struct MapPreparationOptions {
  bool enabled = true;        ///< [topology] places_prepare: false = every free cell is a place (drawn plans)
  double robot_radius = 0.2;  ///< [topology] places_robot_radius (m): the disc a place must lie in
  double view_range = 8.0;    ///< [topology] places_view_range (m): with the path, seen from at most this far (0 = off)
  double min_area = 1.0;      ///< [topology] places_min_area (m^2): smaller groups of places are none
  /// [topology] places_path_step (m): the path is sampled this far apart for the visibility step.
  double path_step = 0.25;
};

/// What the stage found: the places, and how many free cells each step took away.
struct PreparedMap {
  cv::Mat places;           ///< CV_8U, 255 where a free cell is a place
  cv::Mat seen_not_place;   ///< CV_8U, 255 where a cell is free in the map but no place
  std::size_t free_cells = 0, place_cells = 0;
  std::size_t removed_robot_fit = 0, removed_far = 0, removed_unreachable = 0;
};

/// Runs the three steps on `occ` (its free cells). `path` holds the robot's positions in cells (x = column,
/// y = row of occ; empty when unknown: steps 2 and the path part of 3 are skipped). With `o.enabled` false, every
/// free cell is a place. `threads`: the visibility step's rays are cast on that many threads (same result).
PreparedMap prepareMap(const places::OccupancyImage& occ, const MapPreparationOptions& o,
                       const std::vector<cv::Point2d>& path = {}, int threads = 1);

/// The occupancy the place classifier sees: `occ` with the free cells that are no place made unknown.
places::OccupancyImage placesOnly(const places::OccupancyImage& occ, const PreparedMap& prepared);

/// The robot's positions (world metres) as cells of a map of `rows` rows whose cell (0, 0) is the top-left and
/// whose lower-left corner is at `origin` (MapImage's convention): x = (wx − origin.x) / res,
/// y = rows − (wy − origin.y) / res (cell centres at half-integers).
std::vector<cv::Point2d> pathInCells(const std::vector<cv::Point2d>& world, cv::Point2d origin, double resolution,
                                     int rows);

}  // namespace gridtopo::topology
