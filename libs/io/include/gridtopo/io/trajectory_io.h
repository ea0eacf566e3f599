#pragma once
// Trajectory text files: one line per laser scan, "timestamp x y theta" (seconds, metres, radians),
// numbers in shortest round-trip form (full precision). '#' starts a comment line.
#include <mrpt/math/TPose2D.h>

#include <string>
#include <vector>

namespace gridtopo::io {

struct TimedPose {
  double timestamp = 0.0;
  mrpt::math::TPose2D pose{0, 0, 0};
};

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
