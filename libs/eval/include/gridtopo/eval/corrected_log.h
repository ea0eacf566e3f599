#pragma once
// Estimated trajectories stored as CARMEN logs with corrected poses (e.g. GMapping's ".gfs.log"): the laser
// lines carry the corrected pose; their timestamps may be logger timestamps printed with 6 significant digits
// (GMapping), which are matched to the raw log's laser lines to recover the ipc timestamps of the relations.
#include <string>
#include <vector>

#include "gridtopo/io/carmen_log.h"
#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::eval {

enum class CorrectedTimeMatch {
  Auto,    ///< Ipc if every corrected laser line's ipc timestamp is one of the raw log's, else Logger
  Ipc,     ///< the corrected log's ipc timestamps are already the raw log's
  Logger,  ///< nearest raw laser line by logger timestamp (reproduces the benchmark's published figures)
  LoggerAndRanges,  ///< among the raw laser lines whose logger timestamp rounds alike, the one with the same
                    ///< ranges (exact association; differs from Logger in Intel's bursts of scans 1 ms apart)
};

enum class CorrectedPose {
  Robot,  ///< the robot pose of the laser line (FLASER odom_x odom_y odom_theta; ROBOTLASER1 robot pose)
  Laser,  ///< the laser pose of the line (FLASER x y theta)
};

struct CorrectedLogOptions {
  CorrectedTimeMatch match = CorrectedTimeMatch::Auto;
  CorrectedPose pose = CorrectedPose::Robot;
};

const char* toString(CorrectedTimeMatch m);
CorrectedTimeMatch correctedTimeMatchFromString(const std::string& s);  ///< auto|ipc|logger|ranges

/// Poses of the corrected log's laser lines, stamped with the ipc timestamps of the matching laser lines of
/// `raw`. Throws gridtopo::InputError (corrected log's file, line, field) when a line has no match: a logger
/// timestamp further from every raw one than its printed precision allows.
std::vector<io::TimedPose> correctedTrajectory(const io::CarmenLog& corrected, const io::CarmenLog& raw,
                                               const CorrectedLogOptions& options = {},
                                               CorrectedTimeMatch* used = nullptr);

}  // namespace gridtopo::eval
