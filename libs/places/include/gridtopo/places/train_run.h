#pragma once
// gridtopo-train's run: the labelled maps it learns from (the standard maps of a places directory, or given pairs,
// plus the simulated SLAM-like maps of the standard plans), their samples, the model trained on them, and the notes
// the model file carries about its training.
#include <functional>
#include <string>
#include <vector>

#include "gridtopo/places/training.h"

namespace gridtopo::places {

struct TrainRunSpec {
  std::string places_dir = "datasets/places";  ///< the standard labelled maps (standardLabelledMaps), without pairs
  std::vector<std::string> pairs;  ///< "LABELS.png:MAP.png" each; any replaces the standard maps
  std::string ini;                 ///< the training INI (loadTrainingConfig); empty = the defaults
  double resolution = 0.05;        ///< metres per pixel of the images
  int threads = 2;                 ///< worker threads of the scan simulation (overrides the INI's)
};

/// Trains a model as `spec` says: the samples of every labelled map (a progress bar over the maps on stderr), those of
/// the simulated map of each standard plan ([training] simulated_maps), then trainModel, whose messages go to `log`.
/// The model's notes name the maps, the decision list and the validation scores. InputError for threads < 1, a pair
/// without ':', simulated_maps together with pairs, or a map without a labelled free cell.
PlacesModel trainPlacesModel(const TrainRunSpec& spec, const std::function<void(const std::string&)>& log = {});

}  // namespace gridtopo::places
