#pragma once
// The scans gridtopo-import converts: a log read from a file, or the simulated pillar-room log (simulator.h) with its
// ground truth.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "gridtopo/core/output_set.h"
#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/log_reader.h"

namespace gridtopo::sim {

struct ImportSource {
  std::vector<ScanRecord> scans;
  io::ScanLogInfo info;  ///< the reader's; format Simulated for the simulated log
  std::string name;      ///< the input file, or "simulated (N scans, seed S)"
};

/// Reads `input` with `read`, or simulates `simulate` scans of the pillar room with `seed` and, when `ground_truth`
/// is given, stages its true poses there in `outputs` (a trajectory file whose header names the command).
/// std::invalid_argument unless exactly one of `input` and `simulate` is given, or for `ground_truth` without
/// `simulate`.
ImportSource readImportSource(const std::optional<std::string>& input, const std::optional<std::size_t>& simulate,
                              unsigned seed, const std::optional<std::string>& ground_truth,
                              const io::LogReadOptions& read, OutputSet& outputs);

}  // namespace gridtopo::sim
