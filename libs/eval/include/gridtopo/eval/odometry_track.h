#pragma once
// Odometry as a function of time, used by the relations metric to carry an estimated pose over the gap
// between its own timestamp and a relation's timestamp.
#include <mrpt/math/TPose2D.h>

#include <string>
#include <vector>

#include "gridtopo/core/scan_record.h"

namespace gridtopo::eval {

enum class OdometrySource {
  Auto,        ///< the log's ODOM lines if it has any, else the odometry inside the laser lines
  OdomLines,   ///< ODOM messages (what the benchmark's reference tool uses)
  LaserLines,  ///< the robot odometry pose carried by each FLASER / ROBOTLASER1 line
};

const char* toString(OdometrySource s);
/// "auto" | "odom" | "laser"; throws std::invalid_argument otherwise.
OdometrySource odometrySourceFromString(const std::string& s);

/// The element of `sorted` (sorted by timestamp) nearest in time to t. Ties go to the earlier timestamp; among
/// equal timestamps the first element is returned. `sorted` must not be empty.
const TimedPose& nearestInTime(const std::vector<TimedPose>& sorted, double t);

/// Stable sort by timestamp (equal timestamps keep their order).
void sortByTime(std::vector<TimedPose>& poses);

class OdometryTrack {
 public:
  OdometryTrack() = default;
  /// Readings in any order; sorted by time (stable: readings with equal timestamps keep their order).
  explicit OdometryTrack(std::vector<TimedPose> readings);
  /// Picks the readings of a log as any log reader gives it: `odometry` (the log's own odometry messages: CARMEN
  /// ODOM lines, MRPT CObservationOdometry) for OdomLines, the odometry inside the scan records `scans` for
  /// LaserLines; Auto = `odometry` if it is not empty. `used` receives the source actually used.
  static OdometryTrack fromScans(const std::vector<ScanRecord>& scans, const std::vector<OdometryReading>& odometry,
                                 OdometrySource source, OdometrySource* used = nullptr);

  bool empty() const { return poses_.empty(); }
  std::size_t size() const { return poses_.size(); }
  const std::vector<TimedPose>& poses() const { return poses_; }

  /// The reading nearest in time to t (ties: the earlier one in time order).
  const TimedPose& nearest(double t) const;
  /// Odometry at time t linearly interpolated between the two readings around t (x, y linear; theta along the
  /// shorter arc); clamped to the first/last reading outside the covered time span.
  mrpt::math::TPose2D interpolate(double t) const;
  /// nearest(t).pose or interpolate(t).
  mrpt::math::TPose2D at(double t, bool interpolated) const;

 private:
  std::vector<TimedPose> poses_;
};

}  // namespace gridtopo::eval
