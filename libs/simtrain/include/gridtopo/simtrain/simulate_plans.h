#pragma once
// gridtopo-simulate-maps: the simulated SLAM-like map of every standard labelled plan of datasets/places
// (training_map.h), written as OUT/NAME_sim_map.png (pixel-aligned with the plan, so its labels are the plan's
// labelled/training_*.png) plus OUT/manifest.txt (the command's settings and each run's figures), all or nothing.
#include <functional>
#include <string>
#include <vector>

#include "gridtopo/simtrain/training_map.h"

namespace gridtopo::simtrain {

struct SimulatedPlan {
  std::string name;
  int scans = 0;
  double path_length = 0;  ///< m
  int rooms = 0, rooms_entered = 0, rooms_unreachable = 0, corridor_goals = 0;
  double known_fraction = 0;  ///< plan free cells that the map knows (not grey)
  double free_fraction = 0;   ///< plan free cells that the map reads as free (grey >= 204)
};

/// Loads the SLAM's map and beam options ([slam] section of a gridtopo-slam INI, e.g. config-ini/slam.ini) into
/// `o`; an empty path keeps the defaults. InputError names the INI.
void loadSlamMapOptions(const std::string& slam_ini, TrainingMapOptions& o);

/// Simulates the plans of `places_dir` (all standard labelled maps, or those named in `only`) and writes them to
/// `out_dir` in one OutputSet. `progress(done, total, name)` after each map.
std::vector<SimulatedPlan> simulatePlans(const std::string& places_dir, const std::string& out_dir,
                                         const TrainingMapOptions& options, const std::vector<std::string>& only,
                                         const std::string& command_line,
                                         const std::function<void(std::size_t, std::size_t, const std::string&)>& progress = {});

}  // namespace gridtopo::simtrain
