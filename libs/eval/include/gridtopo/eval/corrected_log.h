#pragma once
// Estimated trajectories stored as CARMEN logs with corrected poses (e.g. GMapping's ".gfs.log"): the laser
// lines carry the corrected pose; their timestamps may be logger timestamps printed with 6 significant digits
// (GMapping), which are matched to the raw log's laser lines to recover the ipc timestamps of the relations.
#include <string>
#include <vector>

#include "gridtopo/core/scan_record.h"

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

/// Poses of the corrected log's laser lines (`corrected`: the scan records of that log, as a log reader gives them),
/// stamped with the ipc timestamps of the matching scans of the raw log (`raw`). `corrected_name` / `raw_name`
/// name the logs in errors. Throws gridtopo::InputError (corrected log's name, line, field) when a line has no
/// match: a logger timestamp further from every raw one than its printed precision allows.
std::vector<TimedPose> correctedTrajectory(const std::vector<ScanRecord>& corrected, const std::string& corrected_name,
                                           const std::vector<ScanRecord>& raw, const std::string& raw_name,
                                           const CorrectedLogOptions& options = {}, CorrectedTimeMatch* used = nullptr);

}  // namespace gridtopo::eval
