#pragma once
// Trajectory text files: one line per laser scan, "timestamp x y theta" (seconds, metres, radians),
// numbers in shortest round-trip form (full precision). '#' starts a comment line.
#include <string>
#include <vector>

#include "gridtopo/core/scan_record.h"

namespace gridtopo::io {

/// Writes atomically (temporary file + rename). `header` lines are written as '#' comments.
void writeTrajectory(const std::string& path, const std::vector<TimedPose>& poses,
                     const std::vector<std::string>& header = {});
/// Serialises to a string (the same text writeTrajectory writes).
std::string formatTrajectory(const std::vector<TimedPose>& poses, const std::vector<std::string>& header = {});
/// Reads a trajectory file; throws gridtopo::InputError naming file, line and field on malformed lines.
std::vector<TimedPose> readTrajectory(const std::string& path);

/// Shortest decimal text that reads back to exactly `v` (std::to_chars).
std::string formatDouble(double v);

}  // namespace gridtopo::io
