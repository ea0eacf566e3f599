#pragma once
// What a scan log holds, as gridtopo-import prints it: scans, odometry, beams per scan, time span and backward
// steps, no-return and no-information readings, and what the reader skipped or decided (ScanLogInfo).
#include <cstddef>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/log_reader.h"

namespace gridtopo::io {

/// Counts over a scan stream.
struct LogSummary {
  std::size_t scans = 0, with_odometry = 0, backward_steps = 0, no_return = 0, no_information = 0, beams = 0;
  std::map<std::size_t, std::size_t> beams_per_scan;  // beam count -> scans
  double t_first = 0, t_last = 0, t_min = 0, t_max = 0;
  double max_backward_step = 0;
};

/// The counts of `scans` (timestamps in file order: backward steps are steps to an earlier time).
LogSummary summarizeScans(const std::vector<ScanRecord>& scans);

/// The summary text: input and format, counts, the first scan's geometry, beams per scan, time span, backward
/// steps, readings without a return or information, and (CARMEN) lines, skipped lines and messages, notes, warnings.
void printLogSummary(std::ostream& os, const std::string& input, const ScanLogInfo& info, const LogSummary& s,
                     const LaserScan& first);

}  // namespace gridtopo::io
