#include "gridtopo/core/data_dir.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace gridtopo {

namespace fs = std::filesystem;

std::string executablePath() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : p.string();
}

std::vector<std::string> dataDirs(const std::string& build_time_dir, const std::string& exe_path) {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("GRIDTOPO_DATA_DIR"); env && *env) dirs.emplace_back(env);
  if (!exe_path.empty()) {
    const fs::path prefix = fs::path(exe_path).parent_path().parent_path();
    dirs.push_back((prefix / "share" / "gridtopo" / "datasets").string());
    dirs.push_back((prefix / "datasets").string());
  }
  if (!build_time_dir.empty()) dirs.push_back(build_time_dir);
  return dirs;
}

std::string findDataFile(const std::string& relative, const std::string& build_time_dir, const std::string& exe_path) {
  for (const std::string& d : dataDirs(build_time_dir, exe_path)) {
    std::error_code ec;
    const fs::path p = fs::path(d) / relative;
    if (fs::is_regular_file(p, ec)) return p.string();
  }
  return "";
}

}  // namespace gridtopo
