#pragma once
// A small laser + odometry simulator for tests and experiments: a floor plan made of wall segments, a robot
// driven through waypoints, a laser ray-cast against the walls with range noise, and odometry corrupted with
// noise and a systematic drift. Produces the ScanRecord stream every gridtopo algorithm consumes, plus the
// ground-truth pose of every scan.
#include <cstdint>
#include <vector>

#include "gridtopo/io/scan_record.h"

namespace gridtopo::sim {

struct Segment {
  double x0, y0, x1, y1;
};

struct FloorPlan {
  std::vector<Segment> walls;
  /// Adds the four walls of an axis-aligned rectangle.
  void addRectangle(double x0, double y0, double x1, double y1);
  /// A 20 m × 12 m office floor: outer walls, a corridor loop around a central block of rooms with doors,
  /// and a few pillars, so that a loop around the block needs loop closure.
  static FloorPlan officeLoop();
  /// Distance from (x, y) along direction a to the nearest wall; +inf if none.
  double rayCast(double x, double y, double a) const;
};

struct SimOptions {
  int beams = 181;
  double fov = 3.14159265358979323846;  ///< rad, centred on the robot's heading
  double max_range = 30.0;              ///< readings beyond are "no return" (logged as max_range)
  double range_sigma = 0.01;            ///< m
  double scan_spacing = 0.1;            ///< m of travel between scans (also every 0.1 rad of turning)
  double speed = 0.5;                   ///< m/s, for timestamps
  // odometry noise per scan increment
  double odo_sigma_xy = 0.01;       ///< m per m travelled
  double odo_sigma_theta = 0.01;    ///< rad per m travelled and per rad turned
  double odo_drift_theta = 0.01;    ///< rad per m: systematic heading bias (unmodelled drift)
  mrpt::math::TPose2D sensor_pose{0.1, 0.0, 0.0};
  std::uint64_t seed = 7;
};

struct SimLog {
  std::vector<io::ScanRecord> records;
  std::vector<mrpt::math::TPose2D> truth;  ///< ground-truth robot pose of each record
};

/// Drives through `waypoints` (turning on the spot, then driving straight) and records scans.
SimLog simulate(const FloorPlan& plan, const std::vector<mrpt::math::TPose2D>& waypoints, const SimOptions& o);

/// The waypoints of a loop around the central block of officeLoop(), `laps` times.
std::vector<mrpt::math::TPose2D> officeLoopWaypoints(int laps = 1);

}  // namespace gridtopo::sim
