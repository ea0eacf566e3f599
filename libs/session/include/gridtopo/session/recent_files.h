#pragma once
// Most-recently-used file list, persisted as one path per line (newest first).
#include <string>
#include <vector>

namespace gridtopo::session {

class RecentFiles {
 public:
  explicit RecentFiles(std::size_t capacity = 10) : capacity_(capacity) {}
  void add(const std::string& path);  ///< moves to the front (absolute path), drops the oldest beyond capacity
  void remove(const std::string& path);
  const std::vector<std::string>& paths() const { return paths_; }
  /// Missing or unreadable file: empty list (a recent-files list is a convenience, never an error).
  void load(const std::string& file);
  void save(const std::string& file) const;  ///< atomic; creates the directory
  /// $XDG_CONFIG_HOME/gridtopo/recent-files (or ~/.config/...).
  static std::string defaultFile();

 private:
  std::size_t capacity_;
  std::vector<std::string> paths_;
};

}  // namespace gridtopo::session
