#pragma once
// gridtopo-simulate-maps: the simulated SLAM-like map of every standard labelled plan of datasets/places
// (training_map.h; the exact variant or the SLAM variant), written as OUT/NAME_sim_map.png (pixel-aligned with the
// plan, so its labels are the plan's labelled/training_*.png) plus OUT/manifest.txt (the command's settings and
// each run's figures, for the SLAM variant with its drift), all or nothing.
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
  /// The SLAM variant: its processed scans and how far its map is from the plan.
  std::size_t slam_processed_scans = 0;
  SlamDrift drift;
};

/// Loads the [slam] section of a gridtopo-slam INI (e.g. config-ini/slam.ini) into `o`: all of it into o.slam (the
/// SLAM variant's SLAM), its map and beam options into o.map, o.beams; an empty path keeps the defaults. InputError
/// names the INI.
void loadSlamMapOptions(const std::string& slam_ini, TrainingMapOptions& o);

/// Simulates the plans of `places_dir` (all standard labelled maps, or those named in `only`) and writes them to
/// `out_dir` in one OutputSet. `progress(done, total, name)` after each map; `slam_progress(name, fed, total)` during
/// each SLAM run (SLAM variant).
std::vector<SimulatedPlan> simulatePlans(
    const std::string& places_dir, const std::string& out_dir, const TrainingMapOptions& options,
    const std::vector<std::string>& only, const std::string& command_line,
    const std::function<void(std::size_t, std::size_t, const std::string&)>& progress = {},
    const std::function<void(const std::string&, std::size_t, std::size_t)>& slam_progress = {});

/// One line of gridtopo-simulate-maps' report: scans, path, rooms entered, known and free fractions (and for the
/// SLAM variant its final error and label agreement).
std::string summaryLine(const SimulatedPlan& p, MapVariant variant);

/// gridtopo-simulate-maps' command line, as given.
struct SimulateMapsArgs {
  std::string places_dir = "datasets/places";
  std::string output;                       ///< empty: datasets/places/derived (exact) or derived/slam (slam)
  std::string variant = "exact";            ///< exact | slam
  int threads = -1;                         ///< SLAM threads; < 0: the INI's
  std::string slam_ini = "config-ini/slam.ini";  ///< empty: built-in [slam] defaults
  int seed = 1;
  double room_visit_probability = 0.7;
  double clearance = 0.25;                  ///< m
  std::string maps;                         ///< comma-separated plan names; empty: all
  /// Fraction of the beams logged as no-return (a random dropout; the Intel log has 2.8 %, ACES 0.8 %).
  double no_return_probability = TrainingMapOptions::defaultLaser().dropout_probability;
};

/// What simulatePlans needs for those arguments: the options, the output directory, the plans, and the command line
/// that remakes the maps (written to the manifest).
struct SimulateMapsRun {
  TrainingMapOptions options;
  std::string places_dir, output;
  std::vector<std::string> only;
  std::string command;
};

/// Checks the arguments (InputError naming the flag: --variant, --seed, --room-visit-probability, --clearance,
/// --no-return-probability, and the INI's errors) and loads the [slam] section of the INI.
SimulateMapsRun simulateMapsRunOf(const SimulateMapsArgs& args);

/// "exact" / "slam"; InputError(`field`) otherwise.
MapVariant mapVariantFromString(const std::string& s, const std::string& field = "--variant");
const char* toString(MapVariant v);

}  // namespace gridtopo::simtrain
