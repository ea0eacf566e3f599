#pragma once
// The one laser + odometry simulator of gridtopo, for tests, demos and `gridtopo-import --simulate`: a floor plan
// made of wall segments, a true path (driven through waypoints, or given pose by pose), a laser ray-cast against
// the walls with range noise, and odometry integrated from noisy increments of the true motion (with an optional
// systematic heading drift). Produces the ScanRecord stream every gridtopo algorithm consumes, plus the ground-truth
// pose of every scan. Everything is drawn from one seeded generator: the same inputs give the same log bit for bit.
//
// Two worlds ship with it:
//  - FloorPlan::officeLoop(): a 20 m x 12 m office floor with a corridor loop around a block of rooms (SLAM tests);
//  - FloorPlan::pillarRoom(): a 12 m x 6 m room with two pillars and two wall stubs, driven on an ellipse by
//    simulatePillarRoom() (the log of `gridtopo-import --simulate`).
#include <mrpt/math/TPose2D.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/trajectory_io.h"

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
  /// A 12 m × 6 m room with two 0.6 m square pillars centred at (3, 3) and (9, 3) and two short wall stubs,
  /// (5, 5.4)–(5, 6) and (7, 0)–(7, 0.5).
  static FloorPlan pillarRoom();
  /// A featureless corridor along x: two walls, y = 0 and y = width, from x = 0 to x = length (open at both ends).
  static FloorPlan straightCorridor(double length, double width);
  /// Distance from (x, y) along direction a to the nearest wall; +inf if none.
  double rayCast(double x, double y, double a) const;
};

/// A world the laser senses: the distance from (x, y) along direction a (rad) to the nearest obstacle, +inf if
/// none. FloorPlan::rayCast and GridPlan::rayCast (grid_plan.h) are the two.
using RayCaster = std::function<double(double x, double y, double a)>;

struct SimOptions {
  // Laser: beam k points at −fov/2 + k·fov/(beams−1) in the laser frame.
  int beams = 181;
  double fov = 3.14159265358979323846;  ///< rad, centred on the laser's heading
  bool interleave = false;              ///< odd scans start half an increment later (like some SICK logs)
  double max_range = 30.0;              ///< readings at or beyond are "no return"
  double no_return_range = 0.0;         ///< range logged for a no-return beam; 0 means max_range
  double range_sigma = 0.01;            ///< m, Gaussian range noise
  double range_quantum = 0.0;           ///< readings rounded to this (0.01 like CARMEN logs); 0 keeps them exact
  /// Probability that a beam returns nothing although it meets an obstacle in range (glass, black surfaces);
  /// such a beam is logged as a no-return reading. 0 draws nothing (the logs of earlier versions, bit for bit).
  double dropout_probability = 0.0;
  mrpt::math::TPose2D sensor_pose{0.1, 0.0, 0.0};  ///< laser pose on the robot
  // Driving through waypoints (simulate()): a scan every scan_spacing m of travel or rad of turning.
  double scan_spacing = 0.1;  ///< m of travel between scans (also every 0.1 rad of turning)
  double speed = 0.5;         ///< m/s (rad/s: half of it), for timestamps
  double start_time = 1000.0;  ///< timestamp of the first scan, s
  // Odometry noise per increment between consecutive scans (distance d travelled, angle a turned).
  double odo_sigma_xy = 0.01;            ///< m per m travelled, forward and sideways
  double odo_sigma_theta = 0.01;         ///< rad per rad turned
  double odo_sigma_theta_per_m = 0.01;   ///< rad per m travelled
  double odo_drift_theta = 0.01;         ///< rad per m: systematic heading bias (unmodelled drift)
  std::uint64_t seed = 7;
};

struct SimLog {
  std::vector<ScanRecord> records;
  std::vector<mrpt::math::TPose2D> truth;  ///< ground-truth robot pose of each record
  /// The ground truth with the records' timestamps, as written to trajectory files.
  std::vector<TimedPose> timedTruth() const;
};

/// Senses along a given true path: scan i is taken at truth[i] at time times[i], its odometry is the previous
/// odometry composed with the noisy true increment. Throws std::invalid_argument on inconsistent input.
SimLog simulatePath(const FloorPlan& plan, const std::vector<mrpt::math::TPose2D>& truth,
                    const std::vector<double>& times, const SimOptions& o);
/// The same in any world.
SimLog simulatePath(const RayCaster& world, const std::vector<mrpt::math::TPose2D>& truth,
                    const std::vector<double>& times, const SimOptions& o);

/// Drives through `waypoints` (turning on the spot, then driving straight) and records scans.
SimLog simulate(const FloorPlan& plan, const std::vector<mrpt::math::TPose2D>& waypoints, const SimOptions& o);
/// The same in any world.
SimLog simulate(const RayCaster& world, const std::vector<mrpt::math::TPose2D>& waypoints, const SimOptions& o);

/// The waypoints of a loop around the central block of officeLoop(), `laps` times.
std::vector<mrpt::math::TPose2D> officeLoopWaypoints(int laps = 1);

/// The sensor and odometry of the pillar-room log: 180 beams 1° apart, max range 8 m (the room's diagonal is
/// longer, so some beams see nothing; they report 9 m), 1 cm noise then centimetre rounding, 5 % translation and
/// rotation noise and 0.01 rad/m random heading noise, no bias, seed 42.
SimOptions pillarRoomOptions();

/// The pillar-room log: `scans` poses 0.2 s apart on a counter-clockwise ellipse around both pillars (centre (6, 3),
/// radii 4.5 m × 2 m), starting at its bottom point heading +x; the last scan stops one step short of closing it.
SimLog simulatePillarRoom(std::size_t scans = 200, const SimOptions& o = pillarRoomOptions());

}  // namespace gridtopo::sim
