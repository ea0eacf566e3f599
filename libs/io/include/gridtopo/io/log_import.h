#pragma once
// gridtopo-import's steps: its flags as the reader's and the rawlog writer's options, and the rawlog staged in an
// output set with a progress bar.
#include <string>
#include <vector>

#include "gridtopo/core/output_set.h"
#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/io/rawlog_io.h"

namespace gridtopo::io {

/// The import's choices as words and numbers (gridtopo-import --help).
struct LogImportOptions {
  std::string odometry = "laser";        ///< laser | odom (CARMEN)
  std::string motion_model = "gaussian";  ///< gaussian | thrun (sf layout)
  std::string layout = "sf";             ///< sf | obs
  std::string sensor_label = "LASER";
  double max_range = 50.0;  ///< CARMEN: laser max range (m) when no PARAM gives it
  int compression = -1;     ///< gzip level 0-9; -1 = by the name (.gz: 1)
  bool gz = false;          ///< gzip (level 1) whatever the name
  bool skip_bad_lines = false, rear_laser = false;
};

/// The reader's options; std::invalid_argument naming the flag for a bad max range or odometry word.
LogReadOptions logReadOptions(const LogImportOptions& o);

/// The rawlog writer's options; std::invalid_argument naming the flag for a bad layout, motion model or level.
RawlogWriteOptions rawlogWriteOptions(const LogImportOptions& o);

/// Stages the rawlog of `scans` at `path` in `outputs` (committed by the caller), with a progress bar unless
/// `quiet`. InputError naming `input` when there are no scans. Returns the summary line ("output: ...", newline).
std::string stageRawlog(OutputSet& outputs, const std::string& path, const std::vector<ScanRecord>& scans,
                        RawlogWriteOptions options, bool quiet, const std::string& input);

}  // namespace gridtopo::io
