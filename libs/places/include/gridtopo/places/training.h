#pragma once
// Learning a PlacesModel from labelled maps (pixel codes room 77, corridor 115, doorway 179, other 0):
// samples on the classification lattice, class-balanced AdaBoost for the six binary problems, the decision-list
// order with the best validation score, and relaxation compatibilities from neighbouring labels.
#include <mrpt/config/CLoadableOptions.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gridtopo/places/model.h"
#include "gridtopo/places/occupancy.h"

namespace gridtopo::places {

struct LabelledMap {
  std::string name;
  OccupancyImage occ;
  cv::Mat codes;  ///< CV_8U label codes, same size as occ
};

/// Reads a labelled map and the occupancy image it was drawn on (same size; labels on non-free cells are
/// ignored). Throws gridtopo::InputError for unreadable files or mismatched sizes.
LabelledMap loadLabelledMap(const std::string& name, const std::string& labels_path, const std::string& map_path,
                            double resolution);

struct LabelledMapFiles {
  std::string name, labels, map, benchmark_map, groundtruth;  ///< benchmark map + ground truth of the same building
};
/// The 9 labelled maps of datasets/places (see datasets/README.md), with their benchmark maps.
std::vector<LabelledMapFiles> standardLabelledMaps(const std::string& places_dir);

/// Lattice samples of one map with features and (if `codes` is given) labels (-1 = unlabelled).
struct MapSamples {
  Lattice lattice;
  cv::Mat features;         ///< CV_32F samples x features
  std::vector<int> labels;  ///< per sample
  cv::Mat block_labels;     ///< CV_32S lattice grid of labels (-1 = none)
};
MapSamples computeSamples(const OccupancyImage& occ, const cv::Mat* codes, const ScanSimulationOptions& scan,
                          const FeatureOptions& features,
                          const std::function<void(std::size_t, std::size_t)>& progress = {});

struct TrainingOptions;
/// The key table of [training]: BoostOptions' keys (boostOptionSchema), then TrainingOptions' own.
const OptionSchema<TrainingOptions>& trainingOptionSchema();

/// Loaded, saved, dumped and validated through trainingOptionSchema (section [training] of a training INI).
struct TrainingOptions : TableOptions<TrainingOptions, trainingOptionSchema> {
  static constexpr const char* kSection = "training";
  BoostOptions boost;
  std::string order = "auto";  ///< "auto" (validation) or e.g. "corridor,room,doorway"
  /// Prior correction: 0 = classifiers stay class-balanced, 1 = shifted fully to the maps' class frequencies.
  double prior_weight = 0.5;
  /// Order choice ("auto"): the training maps are split into this many groups (map index modulo k); each group
  /// in turn is the validation set of the six binary classifiers trained on the others, and the order with the
  /// best balanced accuracy over all held-out maps wins. 1 = a single split (maps with index % 3 == 2 held out).
  int order_folds = 3;
  /// At most this many samples per class for the validation classifiers (the final two use
  /// max_samples_per_class); smaller = faster order choice.
  int order_samples_per_class = 5000;
  /// Issue 15: a directory of simulated SLAM-like maps of the labelled plans (`gridtopo-simulate-maps`, e.g.
  /// datasets/places/derived): for every standard labelled map NAME whose NAME_sim_map.png is there, that map is
  /// trained on too, with the plan's labels (it is pixel-aligned with the plan). Empty = off.
  std::string simulated_maps;
  /// The simulated maps are read as the topology reads a SLAM grid (config-ini/topology.ini's grid_free_threshold
  /// and grid_free_opening_radius): grey >= this is free ...
  int simulated_free_threshold = 204;
  /// ... then the free space is opened with this radius (m; places::openFreeSpace).
  double simulated_free_opening_radius = 0.05;
};

/// NAME_sim_map.png in `dir`: the simulated map of the standard labelled map NAME.
std::string simulatedMapPath(const std::string& dir, const std::string& name);
/// NAME_sim_trajectory.txt in `dir`: the robot's poses of that simulated run ("timestamp x y theta", one per scan,
/// in the plan's frame: pixel (col, row) has its centre at ((col + 0.5) res, (rows - row - 0.5) res)), the true
/// poses for the exact variant, the SLAM's for the SLAM variant: what `gridtopo-topology -t` reads.
std::string simulatedTrajectoryPath(const std::string& dir, const std::string& name);
/// The simulated map of a standard labelled map with the plan's labels, read as TrainingOptions says; nothing when
/// options.simulated_maps is empty or holds no map for `files.name`. Throws InputError for unreadable files or a
/// size that differs from the plan's.
std::optional<LabelledMap> loadSimulatedLabelledMap(const LabelledMapFiles& files, const TrainingOptions& options,
                                                    double resolution);

/// Everything a training INI (config-ini/topology_train.ini) sets: [training], [scan_simulation], [features].
struct TrainingConfig {
  TrainingOptions training;
  ScanSimulationOptions scan;
  FeatureOptions features;
};
/// Reads a training INI through the three key tables; an empty path gives the defaults. Errors (missing file, bad
/// value) are InputErrors that name the INI file, the line and "[section] key".
TrainingConfig loadTrainingConfig(const std::string& ini_path);

/// `gridtopo-train --help-options`: every key of [scan_simulation], [features] and [training] with its default,
/// range, unit and help.
std::string trainingOptionsHelp();

struct OrderScore {
  std::array<int, kNumLabels> order{};
  double accuracy = 0, balanced_accuracy = 0;
};

/// Trains on all samples of `maps`. With order "auto", the order is chosen by validation on held-out maps
/// (TrainingOptions::order_folds; balanced accuracy = mean per-class recall), then the chosen classifiers are
/// retrained on all maps.
PlacesModel trainModel(const std::vector<const MapSamples*>& maps, const ScanSimulationOptions& scan,
                       const FeatureOptions& features, const TrainingOptions& options,
                       std::vector<OrderScore>* validation = nullptr,
                       const std::function<void(const std::string&)>& log = {});

std::string orderName(const std::array<int, kNumLabels>& order);

}  // namespace gridtopo::places
