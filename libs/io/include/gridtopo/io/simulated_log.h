#pragma once
// A small simulated laser log with ground truth, for fast tests and demos: a robot drives one closed loop
// (an ellipse) around two pillars in a 12 m x 6 m room, with a laser mounted off centre. Ranges are ray-cast
// against the walls exactly, then get Gaussian noise and centimetre rounding like CARMEN logs; beams that hit
// nothing within max range report max_range + 1 m and are flagged as no return. Odometry is the ground truth
// with noisy increments (it drifts). Everything is drawn from one seeded generator: the same options give
// the same log bit for bit.
#include <mrpt/math/TPose2D.h>

#include <array>
#include <cstddef>
#include <vector>

#include "gridtopo/io/scan_record.h"
#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::io {

struct SimulationOptions {
  std::size_t scans = 200;             ///< scans along the loop (the last one is back near the first pose)
  std::size_t beams = 180;             ///< beams per scan
  double start_deg = -90.0;            ///< angle of the first beam in the laser frame
  double increment_deg = 1.0;          ///< angle between beams
  bool interleave = false;             ///< odd scans start half an increment later (like some SICK logs)
  double max_range = 8.0;              ///< metres; the room's diagonal (13.4 m) is longer, so some beams see nothing
  double range_noise = 0.01;           ///< metres, standard deviation of the range noise
  double odometry_noise_xy = 0.05;     ///< standard deviation of the translation error per metre travelled
  double odometry_noise_phi = 0.05;    ///< standard deviation of the rotation error per radian turned
  double odometry_noise_drift = 0.01;  ///< standard deviation of the rotation error (rad) per metre travelled
  mrpt::math::TPose2D mount{0.1, 0.0, 0.0};  ///< laser pose on the robot
  double start_time = 1000.0;                ///< timestamp of the first scan (s)
  double period = 0.2;                       ///< time between scans (s)
  unsigned seed = 42;
};

struct SimulatedLog {
  std::vector<ScanRecord> scans;        ///< scans with (noisy) odometry
  std::vector<TimedPose> ground_truth;  ///< the true robot pose of every scan
};

/// The simulated world: wall segments {x1, y1, x2, y2} in metres.
const std::vector<std::array<double, 4>>& simulatedWorld();

/// Distance from (x, y) along direction `angle` to the nearest wall (infinity if none).
double castRay(double x, double y, double angle);

SimulatedLog simulateLog(const SimulationOptions& options = {});

}  // namespace gridtopo::io
