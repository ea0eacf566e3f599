#pragma once
// All-or-nothing output: every file of a run is written under a temporary name and renamed into place only
// when the whole run succeeded, so a failed or interrupted run never leaves half-written results behind.
#include <functional>
#include <string>
#include <vector>

namespace gridtopo {

class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  /// Removes the temporary files of an uncommitted set, and the directories add() created for them if they are
  /// empty then.
  ~OutputSet();

  /// Reserves `final_path` and returns the temporary path to write it to (same directory, so the final
  /// rename is atomic). Creates the parent directory if needed (removed again if the set is not committed). The temporary name keeps the final
  /// extension(s) (e.g. "map.gridmap.gz" -> ".map.gridmap.gz.tmp-123-0.gridmap.gz") for writers that pick
  /// the format from the name.
  std::string add(const std::string& final_path);

  /// Convenience: add() then call `writer(tmp_path)`; exceptions propagate (the set stays uncommitted).
  void write(const std::string& final_path, const std::function<void(const std::string&)>& writer);

  /// Renames every temporary file to its final name. Throws std::runtime_error if a file is missing.
  void commit();

  const std::vector<std::string>& finalPaths() const { return finals_; }

 private:
  std::vector<std::string> finals_, temps_;
  std::vector<std::string> created_dirs_;  ///< outermost first
  bool committed_ = false;
};

/// Writes one file atomically: writer(tmp) then rename(tmp, path). On failure nothing is left at `path`.
void writeFileAtomically(const std::string& path, const std::function<void(const std::string&)>& writer);

/// Writes a string to a file atomically.
void writeTextFileAtomically(const std::string& path, const std::string& content);

}  // namespace gridtopo
