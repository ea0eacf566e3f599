#pragma once
// One entry point for every log format: the SLAM and the tools never care where the data came from.
#include <string>
#include <vector>

#include "gridtopo/io/carmen_log.h"
#include "gridtopo/io/scan_record.h"

namespace gridtopo::io {

enum class OdometrySource {
  LaserLines,  ///< CARMEN: the odometry pose inside each laser line (default)
  OdomLines,   ///< CARMEN: ODOM messages interpolated at the scan's timestamp (falls back to LaserLines)
};

struct LogReadOptions {
  CarmenReadOptions carmen;
  OdometrySource odometry = OdometrySource::LaserLines;
};

/// Reads a CARMEN log (.clf/.log/.gz) or an MRPT rawlog (either layout) into scans with odometry, in file order.
/// Throws gridtopo::InputError with file / line (or rawlog entry) / field on bad input.
std::vector<ScanRecord> readScanLog(const std::string& path, const LogReadOptions& options = {});

}  // namespace gridtopo::io
