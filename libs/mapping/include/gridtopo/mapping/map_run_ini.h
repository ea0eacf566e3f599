#pragma once
// A gridtopo-map run as one INI file (MRPT style, like gridtopo-slam's and gridtopo-topology's RUN.ini):
//   [map_run]           input = LOG, output = DIR, model = MODEL (default datasets/models/places_model.yml),
//                       max_scans = N (0 = every scan)
//   [slam]              the filter's options (slam::SlamOptions, config-ini/slam.ini)
//   [topology], [relaxation], [correction]   the topology options (topology::TopologyOptions, config-ini/topology.ini)
//   [topology_builder]  the topology builder's schedule (TopologyBuilderOptions)
// Every section may be missing (defaults). Another section or an unknown key is an InputError naming the file, the
// line, the section and the key. The command-line flags override single values.
#include <cstddef>
#include <optional>
#include <string>

#include "gridtopo/mapping/topology_builder_options.h"
#include "gridtopo/slam/slam_options.h"
#include "gridtopo/slam/slam_run_ini.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::mapping {

inline constexpr const char* kMapRunSection = "map_run";

struct MapRunSpec {
  std::string input;   ///< the log (CARMEN or MRPT rawlog); relative paths are taken from the working directory
  std::string output;  ///< the output directory: OUT/slam, OUT/topology, OUT/options.ini
  std::string model;   ///< the place model (gridtopo-train)
  std::size_t max_scans = 0;  ///< feed only the first max_scans scans; 0 = every scan
  slam::SlamOptions slam;
  topology::TopologyOptions topology;
  TopologyBuilderOptions builder;
  std::string ini;  ///< the RUN.ini this was read from; empty when none
  KeyLines lines;   ///< where [map_run] and its keys stand in the RUN.ini (a flag's value has no line)

  /// `key`'s value is the RUN.ini's (no flag replaced it).
  bool fromIni(const std::string& key) const { return lines.has(key); }

  MapRunSpec();
};

/// The key table of [map_run] (input, output, model, max_scans): its loading (OptionSchema::loadRun: an empty value
/// leaves the key unset, the lines are remembered), the strict check of its keys, its INI text, its help.
const OptionSchema<MapRunSpec>& mapRunSchema();

/// `gridtopo-map --help-options`: every key of every section of its RUN.ini, with default, range, unit and help.
std::string mapRunOptionsHelp();

/// Reads a RUN.ini (the sections above). InputError for an unreadable file, another section, an unknown key or a bad
/// value (with its line).
MapRunSpec loadMapRunIni(const std::string& path);

/// The command line's values (gridtopo-map -i, -o, -m, --max-scans); unset = keep. The SLAM flags (-p, -s, -t) go
/// through slam::overrideOptions.
struct MapRunFlags {
  std::optional<std::string> input, output, model;
  std::optional<long> max_scans;
};
void overrideRun(MapRunSpec& spec, const MapRunFlags& flags);

/// The run a command line names (gridtopo-map): the RUN.ini `run_ini` (if not empty), then the flags. UsageError
/// for neither a RUN.ini nor both -i and -o. (checkMapRunSpec comes with the run: runMapping.)
MapRunSpec mapRunOfCommandLine(const std::string& run_ini, const MapRunFlags& run, const slam::SlamOptionFlags& slam);

/// Checks that the run names its input, output and model, and that the input and the model exist: an InputError
/// naming the RUN.ini, the line and "[map_run] key" for a value of the RUN.ini, the file itself for a flag's.
void checkMapRunSpec(const MapRunSpec& spec);

/// The exact loadable INI of the run (OUT/options.ini): [map_run] with the paths absolute, [slam], the topology
/// option sections and [topology_builder], every key written out.
std::string mapRunIni(const MapRunSpec& spec);

}  // namespace gridtopo::mapping
