#pragma once
// An experiment INI (config-ini/experiments/*.ini documents every key):
//   [experiment]      name, output, base_ini, base_section, description, topology_ini, places_model
//   [record]          success_metric, success_threshold, keep_maps, plots
//   [dataset.NAME]    log, relations, map, plan, plan_labels, plan_segmentation (one section per dataset)
//   [slam]            fixed [slam] options on top of base_ini
//   [topology], [relaxation], [correction]  fixed topology options on top of topology_ini
//   [sweep]           key = value list (`a..b` ranges), zip = key key[, key key ...]; topology keys as
//                     topology.KEY, relaxation.KEY, correction.KEY
// Relative paths are relative to the INI's folder. Every section, key and value is checked here, before anything
// runs: an unknown one, or one given twice, is an InputError naming the file, the line and "[section] key". The file
// is read by core's IniFile (the one INI reader of the apps' RUN.ini files).
#include <string>
#include <vector>

#include "gridtopo/core/ini_file.h"
#include "gridtopo/experiment/sweep.h"

namespace gridtopo::experiment {

/// A key = value of the experiment INI with its line (to name it when its value is refused).
struct IniSetting {
  std::string key, value;
  std::size_t line = 0;
};

/// A fixed topology option: [section] key = value (section: topology, relaxation or correction).
struct TopologySetting {
  std::string section, key, value;
  std::size_t line = 0;
};

struct DatasetSpec {
  std::string name;
  std::string log;        ///< CARMEN log or MRPT rawlog (any input gridtopo-slam reads); empty: a map only
  std::string relations;  ///< Freiburg relations for the error metric; empty: the runs have no error figures
  std::string map;        ///< a map for topology runs without a log (gridtopo-topology's input)
  /// A labelled plan of the same building (gridtopo-topology-compare's --reference-map, --reference-labels,
  /// --reference-segmentation): all three or none.
  std::string plan, plan_labels, plan_segmentation;
  std::size_t line = 0;
  bool hasPlan() const { return !plan.empty(); }
};

/// Which error decides a run's success (against success_threshold; m for trans_*, deg for rot_*).
enum class SuccessMetric { TransMean, TransMax, RotMean, RotMax };
const char* toString(SuccessMetric m);

struct ExperimentSpec {
  std::string path;  ///< the experiment INI
  std::string name;
  std::string description;
  std::string output;  ///< results folder (empty: must come from the command line)
  std::string base_ini;
  std::string base_section = "slam";
  std::vector<DatasetSpec> datasets;  ///< in file order
  std::vector<IniSetting> slam;        ///< fixed [slam] options
  std::string topology_ini;    ///< a topology options INI (config-ini/topology.ini) the topology runs start from
  std::string places_model;    ///< gridtopo-topology's place model (-m)
  std::vector<TopologySetting> topology;  ///< fixed [topology] / [relaxation] / [correction] options
  std::vector<SweepKey> sweep;        ///< in file order; a key with one value is a fixed run parameter
  std::vector<std::vector<std::string>> zip_groups;
  SuccessMetric success_metric = SuccessMetric::TransMean;
  double success_threshold = 0.1;
  bool keep_maps = true;
  std::vector<std::string> plots = {"error", "success", "time"};  ///< and "neff" on request

  const DatasetSpec* dataset(const std::string& name) const;
  /// Every run also builds the topology (gridtopo-topology, then gridtopo-topology-compare against the dataset's
  /// plan when it has one): topology_ini, a topology section or a swept topology key is given.
  bool topologyRuns() const;
};

/// The option sections of a topology run, and whether a [sweep] key ("topology.KEY", ...) names one of them.
constexpr const char* kTopologySections[] = {"topology", "relaxation", "correction"};
bool isTopologyKey(const std::string& sweep_key);

/// The keys of [sweep] that are not [slam] options.
constexpr const char* kRunKeys[] = {"dataset", "max_scans"};

/// Reads and checks an experiment INI (sections, keys, value syntax, files exist). The [slam] values themselves are
/// checked by planExperiment, which loads each run's options.
ExperimentSpec loadExperimentSpec(const std::string& path);
ExperimentSpec parseExperimentSpec(const IniFile& doc);

}  // namespace gridtopo::experiment
