#pragma once
// The leave-one-map-out (LOMO) protocol of gridtopo-topology-eval (doc/evaluation.md, doc/topology.md): for every
// labelled map, a place model trained on the other maps (the fold model) labels the map; the labels are scored
// cell by cell against the map's ground truth before and after relaxation, after region correction (and the
// segment / blob votes when on), with the oracle diagnostics (ground-truth region vote, blob oracle); then the same
// model labels the building's benchmark maps (plain and furnished) and their room segmentation is scored against
// the benchmark's ground truth (Bormann et al., ICRA 2016).
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "gridtopo/eval/evaluation.h"
#include "gridtopo/places/model.h"
#include "gridtopo/places/training.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::eval {

struct LomoOptions {
  topology::TopologyOptions topology;  ///< the inference run on every map (its `threads` also simulate the scans)
  places::TrainingConfig training;     ///< how the fold models are trained (and the scans and features simulated)
  /// Use this model for every map instead of fold models (optimistic when the model saw the map); its scan and
  /// feature options replace `training`'s. `fixed_model_path` names it in the result.
  std::optional<places::PlacesModel> fixed_model;
  std::string fixed_model_path;
  std::string model_cache;   ///< directory of fold models fold_MAP.yml: loaded if present, else trained and saved
  double prior_weight = -1;  ///< >= 0: the fold models' prior correction rescaled to this weight
  bool segmentation = true;  ///< also score the room segmentation of the benchmark maps
  std::string dump_dir;      ///< write label / segmentation images and error overlays here (empty: none)
};

/// Cell-label scores of one labelled map (all against its ground-truth codes).
struct MapLabelScores {
  std::string map;
  std::string order;  ///< the fold model's decision-list order (places::orderName)
  int relaxation_iterations = 0;
  ConfusionMatrix before, after;  ///< before / after relaxation
  ConfusionMatrix corrected;      ///< after the region-correction rules
  ConfusionMatrix segment_vote;   ///< the final labels (= corrected unless the segment vote is on)
  ConfusionMatrix blob_vote;      ///< after the blob vote, before correction (empty when the blob vote is off)
  /// Diagnostics: the oracle region vote (ground-truth regions, relaxed probabilities), the same keeping the
  /// predicted doorways, and the blob oracle (every geometric blob voted with its true majority).
  ConfusionMatrix oracle_region_vote, oracle_region_vote_keep_doorways, blob_oracle;
  /// Adds every matrix of `o` (pooling over maps).
  void add(const MapLabelScores& o);
};

/// Room segmentation of one benchmark map.
struct BenchmarkRun {
  std::string map;  ///< file stem, e.g. lab_ipa_furnitures
  SegmentationScore score;
  double seconds = 0;  ///< labelling + topology
};

struct LomoResult {
  std::string mode;  ///< "leave-one-map-out" or "fixed model PATH"
  bool segment_vote = false, blob_vote = false, segmentation = false;
  int threads = 0;
  std::vector<MapLabelScores> maps;  ///< in the order of the labelled maps
  MapLabelScores pooled;             ///< all maps' matrices added
  std::vector<BenchmarkRun> plain, furnished;  ///< one per labelled map when `segmentation`
};

/// The labelled maps named in `names` (comma-separated; empty = all of `all`, in their order). Throws
/// InputError(option, 0, name, "unknown map name") for a name not in `all`.
std::vector<places::LabelledMapFiles> selectMaps(const std::vector<places::LabelledMapFiles>& all,
                                                 const std::string& names, const std::string& option = "--maps");

/// The model that labels map `held_out`: the fixed model, or one trained on the samples of every other map (on the
/// map itself when it is the only one), loaded from / saved to the model cache, its prior correction rescaled to
/// `prior_weight` when that is >= 0 (InputError when the training INI's prior_weight is not > 0).
places::PlacesModel foldModel(const std::vector<places::MapSamples>& samples, std::size_t held_out,
                              const std::string& held_out_name, const LomoOptions& options,
                              const std::vector<std::optional<places::MapSamples>>& simulated = {});

/// Labels one labelled map with `model` from its precomputed samples, builds its topology and scores every stage
/// (MapLabelScores); writes its pictures to options.dump_dir when set.
MapLabelScores scoreLabelledMap(const places::LabelledMap& map, const places::MapSamples& samples,
                                const places::PlacesModel& model, const LomoOptions& options);

/// Labels the plain and the furnished benchmark map of `files`' building with `model` and scores their room
/// segmentation against its ground truth: {plain, furnished}. InputError for unreadable images or a map and
/// ground truth of different sizes.
std::pair<BenchmarkRun, BenchmarkRun> scoreBenchmarkMaps(const places::LabelledMapFiles& files,
                                                         const places::PlacesModel& model, const LomoOptions& options,
                                                         std::ostream& log);

/// The whole protocol over `maps`: samples of every map, then per map its fold model, scoreLabelledMap and (with
/// options.segmentation) scoreBenchmarkMaps. One line per map (and benchmark map) goes to `log`, with progress
/// bars on a terminal.
LomoResult runLeaveOneMapOut(const std::vector<places::LabelledMapFiles>& maps, const LomoOptions& options,
                             std::ostream& log);

}  // namespace gridtopo::eval
