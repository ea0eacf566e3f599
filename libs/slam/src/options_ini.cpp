#include "gridtopo/slam/options_ini.h"

#include <mrpt/config/CConfigFileMemory.h>

namespace gridtopo::slam {

std::string slamOptionsIni(const SlamOptions& options, const std::string& section) {
  mrpt::config::CConfigFileMemory ini;
  options.saveToConfigFile(ini, section);
  return ini.getContent();
}

}  // namespace gridtopo::slam
