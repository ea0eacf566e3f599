#pragma once
// The loop closure's summary of a gridtopo-slam run, read from the run's stats.txt, so that a score comes with what
// the loop closure did to get it (closures accepted, switched off, the largest correction, the global search).
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gridtopo::eval {

struct LoopClosureSummary {
  std::string path;  ///< the stats.txt it came from
  /// The summary line's counts in its order ("nodes", "searches", "closures", "rejected", ...,
  /// "largest_correction_xy", "largest_correction_theta").
  std::vector<std::pair<std::string, double>> values;
  /// A value by key; nullopt when the line does not hold it (a run of an older gridtopo-slam).
  std::optional<double> get(const std::string& key) const;
};

/// The "# loop_closure: KEY VALUE ..." line of `stats_path`; nullopt when the file does not exist or has no such
/// line (the loop closure was off). InputError naming the file and line when the line is malformed.
std::optional<LoopClosureSummary> readLoopClosureSummary(const std::string& stats_path);

/// The stats.txt beside a trajectory file (gridtopo-slam writes both into its output folder).
std::string statsBesideTrajectory(const std::string& trajectory_path);

/// One line: "loop closure (PATH): N accepted (G global), R switched off, largest correction X m / Y rad; global
/// search: S searches, P proposed, C contradicted, D dropped" (the parts the line holds).
std::string loopClosureSummaryText(const LoopClosureSummary& s);

}  // namespace gridtopo::eval
