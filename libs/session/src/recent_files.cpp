#include "gridtopo/session/recent_files.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "gridtopo/core/output_set.h"

namespace gridtopo::session {

namespace fs = std::filesystem;

void RecentFiles::add(const std::string& path) {
  std::error_code ec;
  const std::string abs = fs::absolute(path, ec).lexically_normal().string();
  const std::string p = ec ? path : abs;
  remove(p);
  paths_.insert(paths_.begin(), p);
  if (paths_.size() > capacity_) paths_.resize(capacity_);
}

void RecentFiles::remove(const std::string& path) {
  paths_.erase(std::remove(paths_.begin(), paths_.end(), path), paths_.end());
}

void RecentFiles::load(const std::string& file) {
  paths_.clear();
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line) && paths_.size() < capacity_)
    if (!line.empty() && std::find(paths_.begin(), paths_.end(), line) == paths_.end()) paths_.push_back(line);
}

void RecentFiles::save(const std::string& file) const {
  std::error_code ec;
  fs::create_directories(fs::path(file).parent_path(), ec);
  std::ostringstream o;
  for (const auto& p : paths_) o << p << "\n";
  writeTextFileAtomically(file, o.str());
}

std::string RecentFiles::defaultFile() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  const fs::path base = xdg && *xdg ? fs::path(xdg) : fs::path(home ? home : ".") / ".config";
  return (base / "gridtopo" / "recent-files").string();
}

}  // namespace gridtopo::session
