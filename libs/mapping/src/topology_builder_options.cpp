#include "gridtopo/mapping/topology_builder_options.h"

#include <ostream>

namespace gridtopo::mapping {

const OptionSchema<TopologyBuilderOptions>& topologyBuilderOptionSchema() {
  using O = TopologyBuilderOptions;
  static const OptionSchema<O> schema = OptionSchema<O>("gridtopo::mapping::TopologyBuilderOptions")
                                            .add("update_every", &O::update_every, OptionRange::any(), "scans",
                                                 "recompute the topology every n processed scans; 0 = on request only");
  return schema;
}

void TopologyBuilderOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                                const std::string& section) {
  topologyBuilderOptionSchema().load(*this, source, section);
}

void TopologyBuilderOptions::saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const {
  topologyBuilderOptionSchema().save(*this, target, section);
}

void TopologyBuilderOptions::dumpToTextStream(std::ostream& out) const {
  topologyBuilderOptionSchema().dump(*this, out);
}

std::vector<std::string> topologyBuilderOptionKeys() { return topologyBuilderOptionSchema().keys(); }

std::string topologyBuilderOptionsIni(const TopologyBuilderOptions& options, const std::string& section) {
  return topologyBuilderOptionSchema().ini(options, section);
}

}  // namespace gridtopo::mapping
