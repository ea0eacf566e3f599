#pragma once
// Scenes for the proposal tests: a map built from simulated scans at their true poses, and one simulated scan.
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/prepared_scan.h"

namespace gridtopo::testing_scene {

/// Inserts every scan of `log` into `map` at its true pose (default map update options).
inline void insertAtTruePoses(slam::GridMap& map, const sim::SimLog& log, const slam::BeamOptions& beams) {
  for (std::size_t i = 0; i < log.records.size(); ++i) {
    const auto ps = slam::prepareScan(log.records[i].scan, beams, map.resolution());
    const auto& t = log.truth[i];
    map.insertScan({t.x, t.y, t.phi}, ps.sensor, ps.map_beams, slam::MapUpdateOptions{});
  }
}

/// The scan `plan` gives at `pose` (sim::simulate with `pose` as its one waypoint and the simulator options `so`),
/// prepared for matching.
inline slam::PreparedScan scanAt(const sim::FloorPlan& plan, const slam::Pose2& pose, const sim::SimOptions& so,
                                 const slam::BeamOptions& beams, double resolution) {
  const auto log = sim::simulate(plan, {{pose.x, pose.y, pose.theta}}, so);
  return slam::prepareScan(log.records.at(0).scan, beams, resolution);
}

}  // namespace gridtopo::testing_scene
