// gridtopo-train: learns the place classifier (AdaBoost decision list + relaxation compatibilities) from
// labelled maps and writes one model file.
#include <mrpt/config/CConfigFile.h>
#include <tclap/CmdLine.h>

#include <filesystem>
#include <iostream>
#include <sstream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/places/training.h"

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
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);
    if (list.getValue()) {
      for (const auto& d : places::featureDescriptions()) std::cout << d << "\n";
      return 0;
    }

    auto [train, scan, feat] = places::loadTrainingConfig(ini.getValue());
    if (threads.getValue() < 1) throw InputError("--threads", "must be >= 1");
    scan.threads = threads.getValue();

    std::vector<std::pair<std::string, std::pair<std::string, std::string>>> inputs;
    std::vector<places::LabelledMapFiles> standard;
    if (pairs.getValue().empty()) {
      standard = places::standardLabelledMaps(dir.getValue());
      for (const auto& f : standard) inputs.push_back({f.name, {f.labels, f.map}});
    } else {
      if (!train.simulated_maps.empty())
        throw InputError(ini.getValue(), 0, "[training] simulated_maps", "applies to the standard maps only, not to --pair");
      for (const auto& p : pairs.getValue()) {
        const auto colon = p.find(':');
        if (colon == std::string::npos) throw InputError("--pair", 0, p, "expected LABELS.png:MAP.png");
        inputs.push_back({fs::path(p.substr(0, colon)).stem().string(), {p.substr(0, colon), p.substr(colon + 1)}});
      }
    }
    std::vector<places::MapSamples> samples;
    std::ostringstream notes;
    notes << "trained by gridtopo-train on:";
    ProgressBar bar(inputs.size(), "features", "maps");
    for (const auto& [name, files] : inputs) {
      const auto lm = places::loadLabelledMap(name, files.first, files.second, res.getValue());
      samples.push_back(places::computeSamples(lm.occ, &lm.codes, scan, feat));
      std::size_t labelled = 0;
      for (int l : samples.back().labels) labelled += l >= 0;
      if (labelled == 0) throw InputError(files.first, "no labelled free cell (codes 77/115/179 on free cells)");
      notes << " " << fs::path(files.first).filename().string();
      bar.update(samples.size(), name);
    }
    // Issue 15: the simulated SLAM-like map of each standard plan, with the plan's labels.
    for (const auto& f : standard)
      if (const auto sim = places::loadSimulatedLabelledMap(f, train, res.getValue())) {
        samples.push_back(places::computeSamples(sim->occ, &sim->codes, scan, feat));
        notes << " " << fs::path(places::simulatedMapPath(train.simulated_maps, f.name)).filename().string();
      }
    bar.finish();
    std::vector<const places::MapSamples*> ptrs;
    for (const auto& s : samples) ptrs.push_back(&s);
    std::vector<places::OrderScore> val;
    places::PlacesModel model = places::trainModel(ptrs, scan, feat, train, &val,
                                                   [](const std::string& m) { std::cerr << m << "\n"; });
    notes << "; decision list " << places::orderName(model.order);
    for (const auto& v : val)
      notes << "; validation " << places::orderName(v.order) << " accuracy " << v.accuracy << " balanced "
            << v.balanced_accuracy;
    model.notes = notes.str();
    if (fs::path(out.getValue()).has_parent_path()) fs::create_directories(fs::path(out.getValue()).parent_path());
    model.save(out.getValue());
    std::cerr << "wrote " << out.getValue() << " (decision list " << places::orderName(model.order) << ", "
              << model.first.stumps.size() << " + " << model.second.stumps.size() << " stumps)\n";
    return 0;
  });
}
