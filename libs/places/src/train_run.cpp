#include "gridtopo/places/train_run.h"

#include <filesystem>
#include <sstream>
#include <utility>

#include "gridtopo/core/error.h"
#include "gridtopo/core/progress.h"

namespace fs = std::filesystem;

namespace gridtopo::places {

namespace {

struct NamedFiles {
  std::string name, labels, map;
};

/// The labelled maps to read: the pairs, else the standard maps.
std::vector<NamedFiles> labelledInputs(const TrainRunSpec& spec, const std::vector<LabelledMapFiles>& standard,
                                       const TrainingOptions& training) {
  std::vector<NamedFiles> inputs;
  for (const auto& f : standard) inputs.push_back({f.name, f.labels, f.map});
  if (spec.pairs.empty()) return inputs;
  if (!training.simulated_maps.empty())
    throw InputError(spec.ini, 0, "[training] simulated_maps", "applies to the standard maps only, not to --pair");
  for (const auto& p : spec.pairs) {
    const auto colon = p.find(':');
    if (colon == std::string::npos) throw InputError("--pair", 0, p, "expected LABELS.png:MAP.png");
    inputs.push_back({fs::path(p.substr(0, colon)).stem().string(), p.substr(0, colon), p.substr(colon + 1)});
  }
  return inputs;
}

}  // namespace

PlacesModel trainPlacesModel(const TrainRunSpec& spec, const std::function<void(const std::string&)>& log) {
  auto [train, scan, feat] = loadTrainingConfig(spec.ini);
  if (spec.threads < 1) throw InputError("--threads", "must be >= 1");
  scan.threads = spec.threads;
  const std::vector<LabelledMapFiles> standard =
      spec.pairs.empty() ? standardLabelledMaps(spec.places_dir) : std::vector<LabelledMapFiles>{};
  const std::vector<NamedFiles> inputs = labelledInputs(spec, standard, train);

  std::vector<MapSamples> samples;
  std::ostringstream notes;
  notes << "trained by gridtopo-train on:";
  ProgressBar bar(inputs.size(), "features", "maps");
  for (const auto& in : inputs) {
    const auto lm = loadLabelledMap(in.name, in.labels, in.map, spec.resolution);
    samples.push_back(computeSamples(lm.occ, &lm.codes, scan, feat));
    std::size_t labelled = 0;
    for (int l : samples.back().labels) labelled += l >= 0;
    if (labelled == 0) throw InputError(in.labels, "no labelled free cell (codes 77/115/179 on free cells)");
    notes << " " << fs::path(in.labels).filename().string();
    bar.update(samples.size(), in.name);
  }
  // Issue 15: the simulated SLAM-like map of each standard plan, with the plan's labels.
  for (const auto& f : standard)
    if (const auto sim = loadSimulatedLabelledMap(f, train, spec.resolution)) {
      samples.push_back(computeSamples(sim->occ, &sim->codes, scan, feat));
      notes << " " << fs::path(simulatedMapPath(train.simulated_maps, f.name)).filename().string();
    }
  bar.finish();

  std::vector<const MapSamples*> maps;
  for (const auto& s : samples) maps.push_back(&s);
  std::vector<OrderScore> validation;
  PlacesModel model = trainModel(maps, scan, feat, train, &validation, log);
  notes << "; decision list " << orderName(model.order);
  for (const auto& v : validation)
    notes << "; validation " << orderName(v.order) << " accuracy " << v.accuracy << " balanced " << v.balanced_accuracy;
  model.notes = notes.str();
  return model;
}

}  // namespace gridtopo::places
