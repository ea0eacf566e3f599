#pragma once
// The options of the topology map builder (CMetricMapBuilderTopology) in MRPT's TLoadableOptions style, read from
// one INI section ([topology_builder] in gridtopo-map's RUN.ini, see config-ini/run-map.ini).
#include <mrpt/config/CLoadableOptions.h>

#include <iosfwd>
#include <string>
#include <vector>

#include "gridtopo/core/option_schema.h"

namespace gridtopo::mapping {

inline constexpr const char* kTopologyBuilderSection = "topology_builder";

struct TopologyBuilderOptions : public mrpt::config::CLoadableOptions {
  /// Recompute the semantic and topological map each time the metric builder's map has grown by this many processed
  /// scans (its getCurrentlyBuiltMapSize: for gridtopo's SLAM the filter's processed steps); 0 = only on request
  /// (updateTopology(), e.g. at the end of a run).
  unsigned update_every = 0;

  /// Reads the keys of `section`; InputError(file, 0, "[section] key", ...) for a value that is not a whole number
  /// >= 0.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) override;
  void saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  void dumpToTextStream(std::ostream& out) const override;
};

/// The key table of [topology_builder] (load, save, dump, help).
const OptionSchema<TopologyBuilderOptions>& topologyBuilderOptionSchema();

/// The keys of the section (for the strict checks of RUN.ini files).
std::vector<std::string> topologyBuilderOptionKeys();

/// The options as a loadable INI section `[section]`.
std::string topologyBuilderOptionsIni(const TopologyBuilderOptions& options,
                                      const std::string& section = kTopologyBuilderSection);

}  // namespace gridtopo::mapping
