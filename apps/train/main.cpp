// gridtopo-train: learns the place classifier (AdaBoost decision list + relaxation compatibilities) from
// labelled maps and writes one model file.
#include <tclap/CmdLine.h>

#include <filesystem>
#include <iostream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/places/features.h"
#include "gridtopo/places/train_run.h"

using namespace gridtopo;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-train", [&]() -> int {
    TCLAP::CmdLine cmd(
        "Train the semantic place classifier of gridtopo (Mozos et al.: AdaBoost on simulated scans, decision list "
        "room/corridor/doorway, relaxation compatibilities) from labelled maps (pixel codes room 77, corridor 115, "
        "doorway 179, other 0) and the occupancy images they were drawn on. Without --pair, uses the 9 labelled "
        "maps of --places-dir.",
        ' ', "0.1");
    TCLAP::ValueArg<std::string> dir("d", "places-dir", "datasets/places directory", false, "datasets/places", "dir", cmd);
    TCLAP::MultiArg<std::string> pairs("p", "pair", "LABELS.png:MAP.png (repeatable); replaces the standard maps",
                                       false, "labels:map", cmd);
    TCLAP::ValueArg<std::string> ini("c", "ini", "training INI (config-ini/topology_train.ini)", false, "", "file", cmd);
    TCLAP::ValueArg<double> res("r", "resolution", "metres per pixel of the images", false, 0.05, "m", cmd);
    TCLAP::ValueArg<int> threads("", "threads", "worker threads", false, 2, "n", cmd);
    TCLAP::ValueArg<std::string> out("o", "output", "model file to write (.yml / .json)", false,
                                     "datasets/models/places_model.yml", "file", cmd);
    TCLAP::SwitchArg list("", "list-features", "print the features (name: formula) and exit", cmd);
    HelpOptionsArg help_options(cmd, places::trainingOptionsHelp);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);
    if (list.getValue()) {
      for (const auto& d : places::featureDescriptions()) std::cout << d << "\n";
      return 0;
    }

    checkOutputFile(out.getValue());  // before the training (minutes), not after it
    places::TrainRunSpec spec;
    spec.places_dir = dir.getValue(), spec.pairs = pairs.getValue(), spec.ini = ini.getValue();
    spec.resolution = res.getValue(), spec.threads = threads.getValue();
    const places::PlacesModel model =
        places::trainPlacesModel(spec, [](const std::string& m) { std::cerr << m << "\n"; });
    OutputSet outs;  // a hidden temporary beside the model (same extension: save picks the format by it), renamed
    outs.write(out.getValue(), [&](const std::string& p) { model.save(p); });
    outs.commit();
    std::cerr << "wrote " << out.getValue() << " (decision list " << places::orderName(model.order) << ", "
              << model.first.stumps.size() << " + " << model.second.stumps.size() << " stumps)\n";
    return 0;
  });
}
