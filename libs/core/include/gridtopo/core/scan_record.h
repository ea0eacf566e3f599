#pragma once
// The data every gridtopo algorithm consumes, whatever the source log (CARMEN .clf/.log/.gz, MRPT rawlog in either
// layout; io holds the readers): laser scans with the robot's odometry at scan time, odometry readings, and timed
// poses (trajectories).
#include <mrpt/math/TPose2D.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gridtopo {

/// One planar laser scan as recorded, in the laser's own frame.
/// Beam k points at angle start_angle + k * angle_increment (radians, counter-clockwise, i.e. right to left
/// for a positive increment) in the laser frame, which sits at sensor_pose in the robot frame.
struct LaserScan {
  double timestamp = 0.0;         ///< seconds; for CARMEN the ipc_timestamp, kept exactly as logged
  double logger_timestamp = 0.0;  ///< CARMEN logger timestamp (0 if the source has none)
  double start_angle = 0.0;       ///< rad, angle of ranges[0] in the laser frame
  double angle_increment = 0.0;   ///< rad between consecutive beams
  double max_range = 0.0;         ///< metres; readings at or beyond it are "no return"
  std::vector<float> ranges;      ///< metres, as logged (no-return readings keep their logged value)
  /// 1 = a real return. 0 = not a return: either "no return" (range >= max_range or +inf: free space up to
  /// the clearing range) or "no information" (NaN, negative, zero).
  std::vector<std::uint8_t> valid;
  mrpt::math::TPose2D sensor_pose{0, 0, 0};  ///< laser pose in the robot frame

  std::size_t size() const { return ranges.size(); }
  double beamAngle(std::size_t k) const { return start_angle + static_cast<double>(k) * angle_increment; }
  /// True for a reading that means "nothing within max_range" (usable to clear free space).
  bool isNoReturn(std::size_t k) const { return !valid[k] && ranges[k] >= max_range; }
};

/// A scan and the robot's odometry pose when it was taken.
struct ScanRecord {
  LaserScan scan;
  bool has_odometry = false;
  mrpt::math::TPose2D odometry{0, 0, 0};  ///< absolute robot pose in the odometry frame at scan time
  std::size_t source_index = 0;           ///< CARMEN: 1-based line number; rawlog: 0-based entry index
};

/// An odometry reading (CARMEN ODOM line, MRPT CObservationOdometry, or the pose inside a laser line).
struct OdometryReading {
  double timestamp = 0.0;
  double logger_timestamp = 0.0;
  mrpt::math::TPose2D pose{0, 0, 0};
  double tv = 0.0, rv = 0.0;  ///< translational / rotational velocity if logged
  std::size_t source_index = 0;
};

/// A pose with its time (an estimated trajectory, odometry as a function of time).
struct TimedPose {
  double timestamp = 0.0;
  mrpt::math::TPose2D pose{0, 0, 0};
};

}  // namespace gridtopo
