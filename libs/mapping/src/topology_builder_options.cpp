#include "gridtopo/mapping/topology_builder_options.h"

#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <ostream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_value.h"

namespace gridtopo::mapping {

void TopologyBuilderOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                                const std::string& section) {
  std::string file = "<ini>";
  if (auto* f = dynamic_cast<const mrpt::config::CConfigFile*>(&source)) file = f->getAssociatedFile();
  try {
    readIniValue(source, section, "update_every", update_every);
  } catch (const InputError& e) {
    throw InputError(file, 0, "[" + section + "] update_every", e.message());
  }
}

void TopologyBuilderOptions::saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const {
  target.write(section, "update_every", static_cast<int>(update_every));
}

void TopologyBuilderOptions::dumpToTextStream(std::ostream& out) const {
  out << "[topology builder] update_every = " << update_every << " processed scans (0 = on request only)\n";
}

std::vector<std::string> topologyBuilderOptionKeys() {
  mrpt::config::CConfigFileMemory mem;
  TopologyBuilderOptions().saveToConfigFile(mem, kTopologyBuilderSection);
  std::vector<std::string> keys;
  mem.getAllKeys(kTopologyBuilderSection, keys);
  return keys;
}

std::string topologyBuilderOptionsIni(const TopologyBuilderOptions& options, const std::string& section) {
  return "[" + section + "]\nupdate_every = " + std::to_string(options.update_every) + "\n";
}

}  // namespace gridtopo::mapping
