#pragma once
// The rawlog reader as libgridtopo_io offers it to libgridtopo_io_core, which loads it when a log turns out to be a
// rawlog (gridtopo/core/lazy_library.h): a C function over types of io_core only.
#include <cstddef>
#include <string>
#include <vector>

#include "gridtopo/core/scan_record.h"

namespace gridtopo::io {

/// What readScanLog takes from readRawlog (rawlog_io.h).
struct RawlogScans {
  std::vector<ScanRecord> scans;
  std::size_t entries = 0;
  std::size_t odometry_observations = 0;
  bool has_actions = false;
};

/// readRawlog(path) into `out`; throws what readRawlog throws.
using ReadRawlogScansFunction = void (*)(const std::string& path, RawlogScans& out);
inline constexpr const char* kReadRawlogScansSymbol = "gridtopo_io_read_rawlog_scans";

}  // namespace gridtopo::io
