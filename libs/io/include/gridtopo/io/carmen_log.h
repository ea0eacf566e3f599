#pragma once
// Reader for CARMEN logs (plain or gzip): FLASER, RLASER, ROBOTLASER1/2, RAWLASER1, ODOM, PARAM and comment
// lines; every other CARMEN message is skipped and counted. Written for gridtopo because MRPT's built-in
// reader gets the aperture of 180-beam scans wrong, ignores ODOM lines and drops the real timestamps.
// doc/carmen.md lists every variant handled and what the reader decides when a log contradicts itself.
#include <cstddef>
#include <istream>
#include <map>
#include <string>
#include <vector>

#include "gridtopo/core/scan_record.h"

namespace gridtopo::io {

struct CarmenReadOptions {
  /// false: the first malformed line throws gridtopo::InputError (file, line, field).
  /// true: malformed lines are skipped, counted and reported in CarmenLog::skipped.
  bool skip_bad_lines = false;
  bool read_rear_laser = false;  ///< also return RLASER / ROBOTLASER2 scans (rear laser) in CarmenLog::scans
  /// Max range (m) of FLASER/RLASER scans when no PARAM robot_front_laser_max / robot_rear_laser_max says
  /// otherwise (CARMEN's default). Readings at or beyond it (Intel's 81.83, ACES's 50.00) are "no return".
  /// Overruled, with a warning, when many readings lie beyond it (see doc/carmen.md, "Max range").
  double default_max_range = 50.0;
  std::size_t max_reported_skips = 100;  ///< how many skipped-line messages CarmenLog::skipped keeps
};

struct CarmenLog {
  std::string path;
  /// Laser scans (FLASER, ROBOTLASER1; RLASER/ROBOTLASER2 if asked; RAWLASER1 or ROBOTLASER0 when the log has
  /// nothing better) in file order. `odometry` of each record is the robot odometry pose inside the laser line,
  /// `scan.sensor_pose` the laser's mounting pose on the robot.
  std::vector<ScanRecord> scans;
  std::vector<OdometryReading> odometry;          ///< ODOM lines in file order
  std::map<std::string, std::string> params;      ///< PARAM name -> value (last one wins)
  std::size_t lines = 0;                          ///< lines read
  std::size_t skipped_lines = 0;                  ///< malformed lines skipped (skip_bad_lines)
  std::vector<std::string> skipped;               ///< messages of the first skipped lines
  /// Well-formed lines of message types gridtopo does not use (TRUEPOS, SYNC, RAWLASER2, RLASER without
  /// read_rear_laser, ...): message type -> lines.
  std::map<std::string, std::size_t> skipped_messages;
  /// What the reader had to decide against the log's own word (units of PARAMs, a max range contradicted by
  /// the readings, repaired timestamps, unknown message types): never silent, printed by gridtopo-import.
  std::vector<std::string> warnings;
  /// Facts about the variant read (PARAM layout, where odometry and scans came from), for summaries.
  std::vector<std::string> notes;
};

/// Reads a CARMEN log; ".gz" files (or gzip magic) are decompressed on the fly.
CarmenLog readCarmenLog(const std::string& path, const CarmenReadOptions& options = {});
/// Parses CARMEN text from a stream; `name` is used in error messages.
CarmenLog parseCarmenLog(std::istream& in, const std::string& name, const CarmenReadOptions& options = {});

}  // namespace gridtopo::io
