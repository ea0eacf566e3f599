// gridtopo-simulate-maps: SLAM-like labelled training maps (issue 15, item 1). For every labelled plan of
// datasets/places, a simulated robot run (a tour of the corridors and rooms, a 180° laser with noise and no-return
// readings, drifting odometry) and the map of its scans, pixel-aligned with the plan: at the true poses (--variant
// exact) or built by the SLAM started at the true start pose (--variant slam).
#include <tclap/CmdLine.h>

#include <iostream>
#include <memory>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/places/training.h"
#include "gridtopo/simtrain/simulate_plans.h"

using namespace gridtopo;

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-simulate-maps", [&]() -> int {
    TCLAP::CmdLine cmd(
        "Simulate a robot mapping run through every labelled plan of datasets/places and write the map of its scans "
        "at the true poses (OUT/NAME_sim_map.png, pixel-aligned with the plan: its labels are the plan's) and "
        "OUT/manifest.txt. --variant slam: the map the SLAM builds from the same scans and odometry instead, started "
        "at the true start pose. Train on them with [training] simulated_maps = OUT.",
        ' ', "0.1");
    TCLAP::ValueArg<std::string> dir("d", "places-dir", "datasets/places directory", false, "datasets/places", "dir", cmd);
    TCLAP::ValueArg<std::string> out("o", "output", "output directory (default datasets/places/derived, for --variant "
                                     "slam datasets/places/derived/slam)", false, "", "dir", cmd);
    TCLAP::ValueArg<std::string> variant("", "variant", "exact (scans at the true poses) or slam (the SLAM's map)",
                                         false, "exact", "exact|slam", cmd);
    TCLAP::ValueArg<int> threads("t", "threads", "SLAM threads (--variant slam; same maps for any count); "
                                 "default: the INI's [slam] threads", false, -1, "n", cmd);
    TCLAP::ValueArg<std::string> slam_ini("c", "slam-ini", "gridtopo-slam INI whose [slam] map and beam options build "
                                          "the maps (config-ini/slam.ini); empty = built-in defaults", false,
                                          "config-ini/slam.ini", "file", cmd);
    TCLAP::ValueArg<int> seed("s", "seed", "seed of the laser and odometry noise and of the rooms entered", false, 1,
                              "n", cmd);
    TCLAP::ValueArg<double> visit("", "room-visit-probability", "each room is entered with this probability", false,
                                  0.7, "p", cmd);
    TCLAP::ValueArg<double> clearance("", "clearance", "m the robot's path keeps from obstacles", false, 0.25, "m", cmd);
    TCLAP::ValueArg<double> no_return("", "no-return-probability", "fraction of the beams logged as no-return (a random "
                                      "dropout; the Intel log has 0.028)", false,
                                      simtrain::SimulateMapsArgs{}.no_return_probability, "p", cmd);
    TCLAP::ValueArg<std::string> maps("", "maps", "comma-separated plan names (default: all 9)", false, "", "names", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    const auto run = simtrain::simulateMapsRunOf(
        {dir.getValue(), out.getValue(), variant.getValue(), threads.getValue(), slam_ini.getValue(), seed.getValue(),
         visit.getValue(), clearance.getValue(), maps.getValue(), no_return.getValue()});
    ProgressBar bar(run.only.empty() ? places::standardLabelledMaps(run.places_dir).size() : run.only.size(),
                    "simulated maps", "maps");
    std::unique_ptr<ProgressBar> scans;  // the SLAM's scans of the current map
    const auto runs = simtrain::simulatePlans(
        run.places_dir, run.output, run.options, run.only, run.command,
        [&](std::size_t done, std::size_t, const std::string& name) { bar.update(done, name); },
        [&](const std::string& name, std::size_t fed, std::size_t total) {
          if (!scans) scans = std::make_unique<ProgressBar>(total, "SLAM " + name, "scans");
          scans->update(fed);
          if (fed == total) scans->finish(), scans.reset();
        });
    bar.finish();
    for (const auto& p : runs) std::cout << simtrain::summaryLine(p, run.options.variant) << "\n";
    return 0;
  });
}
