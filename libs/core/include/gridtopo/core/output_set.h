#pragma once
// All-or-nothing output: every file of a run is written under a temporary name and moved into place only when the
// whole run succeeded, so a failed or interrupted run never leaves half-written results behind (doc/formats.md,
// "What a run guarantees").
//
// An OutputSet over a folder (`OutputSet set(OUT)`) is one transaction for that folder: every file under OUT is
// written into a hidden stage folder beside it (`.OUT.tmp-PID-N`, same file system), and commit() swaps the stage
// in with one rename (renameat2 RENAME_EXCHANGE; the old folder stays whole until the new one is complete, then
// is removed). When OUT holds entries the run does not write (a user's files, outputs of an earlier run with other
// options) it is never replaced: the run's files are moved into it one by one instead, each with one rename, and
// everything is put back as it was if one fails. The stage is removed on every error path (destructor), on
// SIGINT / SIGTERM / SIGHUP once installOutputCleanupOnSignals() ran (every app's runApp does), and a stage left
// by a process that no longer exists (SIGKILL) is removed by the next set over the same folder. A signal that
// arrives during commit() waits until the commit is done.
#include <functional>
#include <string>
#include <vector>

namespace gridtopo {

class OutputSet {
 public:
  /// A set of files staged one by one beside their final names (hidden temporary files).
  OutputSet() = default;
  /// A transaction for the folder `folder`: files added under it are staged in one hidden folder beside it.
  explicit OutputSet(const std::string& folder);
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  /// Removes the temporary files and the stage of an uncommitted set, and the directories it created for them if
  /// they are empty then.
  ~OutputSet();

  /// Reserves `final_path` and returns the temporary path to write it to (same file system, so the final rename
  /// is atomic). Under the set's folder the temporary path is the final name inside the stage folder; elsewhere
  /// it keeps the final extension(s) (e.g. "map.gridmap.gz" -> ".map.gridmap.gz.tmp-123-0.gridmap.gz") for
  /// writers that pick the format from the name. Creates the parent directories if needed (removed again if the
  /// set is not committed).
  std::string add(const std::string& final_path);

  /// add() then `writer(tmp_path)`. A writer's failure is rethrown as std::runtime_error naming the final file
  /// (never the temporary one) and the system's reason; a writer that returns while its file system has no free
  /// block left fails with "No space left on device".
  void write(const std::string& final_path, const std::function<void(const std::string&)>& writer);

  /// Moves every file into place, all together or not at all. Throws std::runtime_error (naming the final path and
  /// the system's reason) if a file is missing or a rename fails; what was there before is then put back.
  void commit();

  const std::vector<std::string>& finalPaths() const { return finals_; }
  /// The stage folder (empty before the first file under the set's folder).
  const std::string& stageFolder() const { return stage_; }

 private:
  void ensureStage();
  void commitStage();

  std::string folder_;  ///< absolute, normalised; empty: no folder transaction
  std::string stage_;
  int stage_slot_ = -1;
  std::vector<std::string> finals_, temps_;
  std::vector<bool> staged_;       ///< per file: inside the stage folder
  std::vector<int> slots_;         ///< signal-cleanup slots of the loose temporary files
  std::vector<std::string> created_dirs_;  ///< outermost first
  bool committed_ = false;
};

/// Checks before a run starts that `folder` can be an output folder: not a regular file, its parent creatable and
/// writable (a stage folder is made there and removed again, so the check does what commit needs), not a mount
/// point. Throws InputError(folder, "cannot write the output folder: <system's reason>").
void checkOutputFolder(const std::string& folder);

/// Checks before a run starts that the file `path` can be written: not a directory, its folder creatable and
/// writable. Throws InputError(path, ...).
void checkOutputFile(const std::string& path);

/// Installs the SIGINT / SIGTERM / SIGHUP handler that removes every uncommitted set's temporary files and stage
/// folders (async-signal-safe: raw system calls only), then dies of the signal as it would have (exit 130 / 143).
/// Called by runApp; idempotent.
void installOutputCleanupOnSignals();

/// Writes one file atomically: writer(tmp) then rename(tmp, path). On failure nothing is left at `path`.
void writeFileAtomically(const std::string& path, const std::function<void(const std::string&)>& writer);

/// Writes a string to a file atomically; a failed write names the file and the system's reason.
void writeTextFileAtomically(const std::string& path, const std::string& content);

}  // namespace gridtopo
