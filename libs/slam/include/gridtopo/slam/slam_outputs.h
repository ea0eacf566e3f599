#pragma once
// The output set of a SLAM run, written by one function for gridtopo-slam and the GUI: map.png,
// map_trajectory.png, map.pgm + map.yaml (ROS map_server), map.gridmap.gz (MRPT), map.simplemap, trajectory.txt,
// stats.txt, options.ini; all or nothing (gridtopo::OutputSet). libgridtopo_slam: MRPT's maps and observations,
// OpenCV's codecs, over libgridtopo_slam_core's SlamResult.
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimpleMap.h>

#include <string>
#include <vector>

#include "gridtopo/core/output_set.h"
#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/rbpf_slam.h"
#include "gridtopo/slam/slam_result.h"
#include "gridtopo/slam/trajectory_tree.h"

namespace gridtopo::slam {

/// The processed scans along the path that ends at `leaf` (the best particle's), at its poses: MRPT's simple map.
mrpt::maps::CSimpleMap simpleMapOf(const TrajectoryNodePtr& leaf, const std::vector<ScanRecord>& scans);
/// The scans `scan_indices` at `poses` (the loop closure's optimised poses): MRPT's simple map.
mrpt::maps::CSimpleMap simpleMapAt(const std::vector<std::size_t>& scan_indices, const std::vector<Pose2>& poses,
                                   const std::vector<ScanRecord>& scans);

struct SlamOutputs {
  mrpt::maps::COccupancyGridMap2D grid;   ///< the best particle's map (toOccupancyGrid)
  std::vector<TimedPose> trajectory;  ///< a pose for every scan
  std::vector<ClosureLine> closures;  ///< the accepted loop closures at the result's poses (map_trajectory.png)
  std::vector<std::string> trajectory_header;  ///< '#' lines of trajectory.txt
  mrpt::maps::CSimpleMap simplemap;       ///< simpleMapOf
  std::string stats;                      ///< the text of stats.txt
  std::string options_ini;                ///< the text of options.ini (slamOptionsIni)
};

/// Writes the whole set into `dir` (created if needed), or nothing: throws on the first failure.
void writeSlamOutputs(const std::string& dir, const SlamOutputs& out);
/// The output set of a run's result: the map as MRPT's occupancy grid (toOccupancyGrid; `result.map` is freed once
/// converted, and the freed memory given back), then the simple map of its scans (simpleMapAt). `result` is consumed.
SlamOutputs exportSlamResult(SlamResult&& result);
/// writeSlamOutputs(dir, exportSlamResult(result)).
void writeSlamResult(const std::string& dir, SlamResult&& result);

/// Writes the set's files into `dir` as temporary files of `set`, which the caller commits with its other files
/// (gridtopo-map: the SLAM and the topology output sets land together or not at all).
/// The set must be a folder transaction (OutputSet(folder)) with `dir` inside or equal to its folder: the ROS
/// map pair is written side by side under its final names in the set's stage folder.
void addSlamOutputs(OutputSet& set, const std::string& dir, const SlamOutputs& out);

}  // namespace gridtopo::slam
