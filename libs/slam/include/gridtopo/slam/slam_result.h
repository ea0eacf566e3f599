#pragma once
// What a SLAM run leaves for its output set, in gridtopo's own types: the map, the trajectory, the loop closures, the
// scans of the simple map and the texts. libgridtopo_slam_core makes it (SlamRun::finishResult) without MRPT's maps;
// libgridtopo_slam turns it into the output set (exportSlamResult, writeSlamResult in slam_outputs.h).
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/pose2.h"
#include "gridtopo/slam/rbpf_slam.h"  // StepStats

namespace gridtopo::slam {

/// A loop closure drawn on the map: the two poses it joins (the matched submap's first scan, the closing scan).
struct ClosureLine {
  Pose2 from, to;
  bool global = false;  ///< found by the global search (drawn orange, as in the GUI)
};

struct SlamResult {
  GridMap map;                        ///< the result's map (SlamRun::resultMap)
  std::vector<TimedPose> trajectory;  ///< a pose for every scan
  std::vector<ClosureLine> closures;  ///< the accepted loop closures at the result's poses
  std::vector<std::string> trajectory_header;  ///< '#' lines of trajectory.txt
  /// The simple map: the processed scans `scan_indices` of `scans` at `scan_poses` (the loop closure's optimised
  /// poses, or the best particle's path without loop closure).
  std::shared_ptr<const std::vector<ScanRecord>> scans;
  std::vector<std::size_t> scan_indices;
  std::vector<Pose2> scan_poses;
  std::string stats;        ///< the text of stats.txt
  std::string options_ini;  ///< the text of options.ini (slamOptionsIni)
};

/// Keeps of `result.scans` only the scans of the simple map (`scan_indices` renumbered 0, 1, ...), and gives the
/// memory of the others back: what the outputs need of a finished run's log, a quarter to a tenth of it. A no-op
/// when the scans are shared with someone else (a run still alive, the GUI).
void keepOnlySimpleMapScans(SlamResult& result);

/// The columns of a stats.txt row as statsRow writes them (a writer may append its own, e.g. the process RSS).
inline constexpr const char* kStatsColumns =
    "step scan_index timestamp time_s neff resampled particles failed_matches evaluations unique_tiles map_bytes "
    "lineages coalescence";
/// One processed step's row of stats.txt (kStatsColumns, space-separated, no newline).
std::string statsRow(const StepStats& s);

/// writeSlamResult (slam_outputs.h), from libgridtopo_slam loaded now if this process has not loaded it
/// (gridtopo/core/lazy_library.h): gridtopo-slam runs the filter without MRPT's maps and OpenCV's codecs and loads
/// them for its outputs only, once the particles are freed. `result` is consumed.
void writeSlamResultLoadingExport(const std::string& dir, SlamResult& result);

}  // namespace gridtopo::slam
