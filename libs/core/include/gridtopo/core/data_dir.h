#pragma once
// Where the data gridtopo ships (the source tree's datasets/: models/places_model.yml, ...) is found at run time,
// so a program does not depend on the path of the tree it was built from.
#include <string>
#include <vector>

namespace gridtopo {

/// This program's executable (/proc/self/exe resolved), or "" when it cannot be found.
std::string executablePath();

/// The folders that may hold the shipped data, in the order they are searched:
///  1. $GRIDTOPO_DATA_DIR, when set and not empty;
///  2. beside the executable `exe_path` (BIN = its folder): BIN/../share/gridtopo/datasets (an installed tree),
///     then BIN/../datasets (a tree copied with its bin/ folder);
///  3. `build_time_dir` (e.g. the source tree's datasets/ known at build time), the last resort.
/// Empty entries are left out.
std::vector<std::string> dataDirs(const std::string& build_time_dir = "",
                                  const std::string& exe_path = executablePath());

/// `dir/relative` for the first folder of dataDirs() where it is a regular file, or "" when none has it.
std::string findDataFile(const std::string& relative, const std::string& build_time_dir = "",
                         const std::string& exe_path = executablePath());

}  // namespace gridtopo
