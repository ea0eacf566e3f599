#pragma once
// An experiment INI (config-ini/experiments/*.ini documents every key):
//   [experiment]      name, output, base_ini, base_section, description
//   [record]          success_metric, success_threshold, keep_maps, plots
//   [dataset.NAME]    log, relations (one section per dataset)
//   [slam]            fixed [slam] options on top of base_ini
//   [sweep]           key = value list (`a..b` ranges), zip = key key[, key key ...]
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

struct DatasetSpec {
  std::string name;
  std::string log;        ///< CARMEN log or MRPT rawlog (any input gridtopo-slam reads)
  std::string relations;  ///< Freiburg relations for the error metric; empty: the runs have no error figures
  std::size_t line = 0;
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
  std::vector<SweepKey> sweep;        ///< in file order; a key with one value is a fixed run parameter
  std::vector<std::vector<std::string>> zip_groups;
  SuccessMetric success_metric = SuccessMetric::TransMean;
  double success_threshold = 0.1;
  bool keep_maps = true;
  std::vector<std::string> plots = {"error", "success", "time"};  ///< and "neff" on request

  const DatasetSpec* dataset(const std::string& name) const;
};

/// The keys of [sweep] that are not [slam] options.
constexpr const char* kRunKeys[] = {"dataset", "max_scans"};

/// Reads and checks an experiment INI (sections, keys, value syntax, files exist). The [slam] values themselves are
/// checked by planExperiment, which loads each run's options.
ExperimentSpec loadExperimentSpec(const std::string& path);
ExperimentSpec parseExperimentSpec(const IniFile& doc);

}  // namespace gridtopo::experiment
