#pragma once
// The options of a run as the INI file that reproduces it (OUT/options.ini of gridtopo-slam and of the GUI's
// Save SLAM outputs): one writer, so both files load back with `gridtopo-slam -c` and the GUI's SLAM > Load INI.
#include <string>

#include "gridtopo/slam/slam_options.h"

namespace gridtopo::slam {

/// A loadable INI text: `[section]` with every key of SlamOptions::saveToConfigFile (doubles to 17 digits), which
/// SlamOptions::loadFromConfigFile reads back to the same options.
std::string slamOptionsIni(const SlamOptions& options, const std::string& section = "slam");

}  // namespace gridtopo::slam
