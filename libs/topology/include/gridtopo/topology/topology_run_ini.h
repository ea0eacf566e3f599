#pragma once
// A topology run as an INI file, like gridtopo-slam's RUN.ini (and MRPT's `rbpf-slam CONFIG.ini`):
// `gridtopo-topology RUN.ini` reads
//   [topology_run]  map = MAP, model = MODEL (default datasets/models/places_model.yml), output = DIR
//   [topology], [relaxation], [correction]  the options (TopologyOptions, config-ini/topology.ini)
// and the command-line flags override single values. A RUN.ini holds no other section and no unknown key (both are
// InputErrors naming the file, the line, the section and the key). The options.ini a run writes is this INI with
// the paths absolute, so loading it again as RUN.ini (or its options with -c) reproduces the run.
#include <optional>
#include <string>
#include <vector>

#include "gridtopo/topology/pipeline.h"

namespace gridtopo::topology {

inline constexpr const char* kTopologyRunSection = "topology_run";
inline constexpr const char* kDefaultPlacesModel = "datasets/models/places_model.yml";
/// The shipped place model inside a data folder (gridtopo::dataDirs()).
inline constexpr const char* kShippedPlacesModel = "models/places_model.yml";

/// `model`, or, when it is the default kDefaultPlacesModel and no such file exists from the working directory, the
/// shipped model found by gridtopo::findDataFile(kShippedPlacesModel) ($GRIDTOPO_DATA_DIR, beside the
/// executable, the source tree's datasets/): the apps then work from any directory. Unchanged when none has it (the
/// reader then names the missing file).
std::string placesModelPath(const std::string& model);

struct TopologyRunSpec {
  std::string map;     ///< the occupancy map; relative paths are taken from the working directory
  std::string model = kDefaultPlacesModel;  ///< the place model (gridtopo-train)
  std::string output;  ///< the output directory
  /// The robot's trajectory while the map was built (gridtopo-slam's trajectory.txt, in the map's frame); empty when
  /// unknown. The map preparation weighs it (which free cells the robot saw from near and can reach).
  std::string trajectory;
  TopologyOptions options;
  std::string ini;     ///< the RUN.ini this was read from; empty when none
  KeyLines lines;      ///< where [topology_run] and its keys stand in the RUN.ini (a flag's value has no line)

  /// `key`'s value is the RUN.ini's (no flag replaced it).
  bool fromIni(const std::string& key) const { return lines.has(key); }
};

/// The option sections of a topology run, in the order topologyOptionsIni writes them.
inline constexpr const char* kTopologyOptionSections[] = {"topology", "relaxation", "correction"};

/// The key table of [topology_run] (map, model, output): its loading (OptionSchema::loadRun: an empty value leaves
/// the key unset, the lines are remembered), the strict check of its keys, its INI text, its help.
const OptionSchema<TopologyRunSpec>& topologyRunSchema();

/// The keys of one option section ("topology", "relaxation" or "correction"): their key tables'. For the strict
/// checks of RUN.ini files that hold the topology options (gridtopo-topology's, gridtopo-map's).
std::vector<std::string> topologyOptionKeys(const std::string& section);

/// `gridtopo-topology --help-options`: every key of [topology_run] and the option sections, with default, range,
/// unit and help.
std::string topologyRunOptionsHelp();

/// Reads a RUN.ini: [topology_run] and the option sections (each may be missing: defaults). InputError for an
/// unreadable file, another section, an unknown key or a bad value.
TopologyRunSpec loadTopologyRunIni(const std::string& path);

/// Reads an options INI given with `-c` (config-ini/topology.ini) strictly: a text file; [topology] required;
/// unknown sections (any but a gridtopo app's) and unknown keys of [topology], [relaxation], [correction] refused
/// with file, line and a "did you mean"; value errors with their line. An empty path gives the defaults.
TopologyOptions loadTopologyOptionsIni(const std::string& path);

/// The command line's values over a run (gridtopo-topology -m, -o, -t, -r, --threads); unset = keep.
struct TopologyRunFlags {
  std::optional<std::string> model, output, trajectory;
  std::optional<double> resolution;
  std::optional<int> threads;
};

/// Sets the given flags' values: InputError("--resolution" / "--threads", ...) for a value out of range.
void overrideRun(TopologyRunSpec& spec, const TopologyRunFlags& flags);

/// Checks that the run names a map and an output, and that the files its RUN.ini names exist: an InputError
/// naming the RUN.ini, the line and "[topology_run] key". (Files named by flags are checked by their readers.)
void checkTopologyRunSpec(const TopologyRunSpec& spec);

/// The run a command line names (gridtopo-topology): `first` is a RUN.ini (it ends in .ini) or the map, whose
/// options then come from the options INI `options_ini` (-c; the defaults without it); then the flags; checked
/// (checkTopologyRunSpec). UsageError for a RUN.ini together with -c, or a map without -o.
TopologyRunSpec topologyRunOfCommandLine(const std::string& first, const std::optional<std::string>& options_ini,
                                         const TopologyRunFlags& flags);

/// The exact loadable INI of the run: [topology_run] (paths absolute), then topologyOptionsIni.
std::string topologyRunIni(const TopologyRunSpec& spec);

}  // namespace gridtopo::topology
