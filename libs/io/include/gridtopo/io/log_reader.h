#pragma once
// One entry point for every log format: the SLAM and the tools never care where the data came from.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "gridtopo/io/carmen_log.h"
#include "gridtopo/core/scan_record.h"

namespace gridtopo::io {

enum class OdometrySource {
  LaserLines,  ///< CARMEN: the odometry pose inside each laser line (default)
  OdomLines,   ///< CARMEN: ODOM messages interpolated at the scan's timestamp (falls back to LaserLines)
};

struct LogReadOptions {
  CarmenReadOptions carmen;
  OdometrySource odometry = OdometrySource::LaserLines;
};

enum class LogFormat {
  Empty,      ///< an empty file (no scans, whatever the format)
  Carmen,     ///< CARMEN text log, plain or gzip
  Rawlog,     ///< MRPT rawlog (either layout), plain or gzip
  Simulated,  ///< not a file: io::simulateLog (never returned by detectLogFormat)
};
const char* logFormatName(LogFormat format);

/// Decides the format from the file's content (after gzip decompression), not its name: a file starting with
/// an MRPT object header (class-name length byte + class name) is a rawlog, anything else is read as CARMEN
/// text (whose parser reports garbage line by line). Throws gridtopo::InputError if the file is missing or
/// unreadable.
LogFormat detectLogFormat(const std::string& path);

/// What readScanLog found besides the scans (for summaries).
struct ScanLogInfo {
  LogFormat format = LogFormat::Empty;
  std::size_t odometry_messages = 0;   ///< CARMEN ODOM lines / rawlog CObservationOdometry objects
  std::size_t lines_or_entries = 0;    ///< CARMEN lines / rawlog top-level objects
  std::size_t skipped_lines = 0;       ///< CARMEN malformed lines skipped (skip_bad_lines)
  std::vector<std::string> skipped;    ///< messages of the first skipped lines
  std::map<std::string, std::size_t> skipped_messages;  ///< CARMEN message types not used -> lines
  std::vector<std::string> warnings;   ///< CARMEN: what the reader decided against the log's word
  std::vector<std::string> notes;      ///< CARMEN: which variant was read (PARAM layout, odometry source)
  std::size_t odometry_fallbacks = 0;  ///< OdomLines: scans outside the ODOM time range (laser-line odometry)
  bool rawlog_has_actions = false;     ///< rawlog in the action / sensory-frame layout
};

/// Reads a CARMEN log (.clf/.log/.gz) or an MRPT rawlog (either layout) into scans with odometry, in file order.
/// `options.carmen` and `options.odometry` apply to CARMEN logs only (rawlogs: see readRawlog).
/// Throws gridtopo::InputError with file / line (or rawlog entry) / field on bad input.
std::vector<ScanRecord> readScanLog(const std::string& path, const LogReadOptions& options = {});
/// The same, also filling `info`.
std::vector<ScanRecord> readScanLog(const std::string& path, const LogReadOptions& options, ScanLogInfo& info);

/// ODOM readings interpolated at each scan's timestamp (linear in x, y, shortest way in theta) between the two
/// readings that bracket it in time (readings sorted by timestamp, ties in file order). Scans outside the ODOM
/// time range keep their own odometry; returns how many did.
std::size_t interpolateOdometry(std::vector<ScanRecord>& scans, const std::vector<OdometryReading>& odometry);

}  // namespace gridtopo::io
