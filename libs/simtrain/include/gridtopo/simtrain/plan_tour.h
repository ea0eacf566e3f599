#pragma once
// The path of a simulated robot run through a labelled floor plan (issue 15, item 1): from the deepest corridor
// cell, a tour that passes every part of the corridors and enters the rooms through their doorways, like a robot
// mapping a building. Planned on the plan's free cells kept `clearance` away from every obstacle; each leg goes to
// the nearest goal not yet reached (least-cost path that keeps to the middle of corridors and doors). Deterministic:
// the same plan and options give the same tour.
#include <mrpt/math/TPose2D.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace gridtopo::simtrain {

struct TourOptions {
  double clearance = 0.25;             ///< m: the robot's path keeps this far from every obstacle ...
  double door_clearance = 0.1;         ///< m: ... except in doorway cells (narrow doors of some plans)
  double corridor_goal_spacing = 3.0;  ///< m: the corridors are cut in squares of this side; each is visited
  double min_room_area = 1.0;          ///< m²: smaller room regions are not goals
  /// Each room is entered with this probability (drawn per room from `seed`); rooms not entered are seen from the
  /// corridor only, through their doors, as in a real mapping run.
  double room_visit_probability = 1.0;
  std::uint64_t seed = 1;
};

struct Tour {
  std::vector<cv::Point> cells;                  ///< the path, pixel by pixel (x = col, y = row)
  std::vector<mrpt::math::TPose2D> waypoints;    ///< the path simplified to straight legs, in the plan's frame
  int rooms = 0;                                 ///< room regions of at least min_room_area
  int rooms_entered = 0;                         ///< rooms whose goal the tour reaches
  int rooms_unreachable = 0;                     ///< rooms with no reachable cell `clearance` from the walls
  int corridor_goals = 0;                        ///< corridor squares visited
  double length = 0;                             ///< m, along the waypoints
  /// Per room region (index = room id - 1 of `room_ids`): entered or not.
  std::vector<bool> room_entered;
  cv::Mat room_ids;                              ///< CV_32S room region id of each pixel (0 = none)
};

/// `free_cells`: CV_8U, non-zero = free; `codes`: CV_8U labels (room 77, corridor 115, doorway 179) of the same
/// size; pixel (col, row) has its centre at ((col + 0.5) res, (rows - row - 0.5) res) (sim::GridPlan's frame).
/// Throws gridtopo::InputError (naming `source`) when the plan has no corridor cell the robot fits in.
Tour planTour(const cv::Mat& free_cells, const cv::Mat& codes, double resolution, const TourOptions& options,
              const std::string& source = "<plan>");

}  // namespace gridtopo::simtrain
