#pragma once
// What gridtopo-map says on stderr while it runs (mapping::runMapping's hooks): the log reader's warnings (always),
// its notes, a progress bar that shows the latest topology's counts, and each topology update when there is no bar
// (a pipe or a file); with `quiet` only the warnings. Then the run's one summary line.
#include <cstddef>
#include <optional>
#include <ostream>
#include <string>

#include "gridtopo/core/progress.h"
#include "gridtopo/mapping/map_run.h"

namespace gridtopo::mapping {

/// "R rooms, C corridors, D doorways, E edges" of the topology's graph.
std::string topologyCounts(const topology::TopologicalGraph& graph);

class MapRunConsole {
 public:
  /// `input` names the log in the reader's messages; `err` receives the messages (the bar draws on stderr).
  MapRunConsole(std::string input, bool quiet, std::ostream& err);
  /// The hooks for runMapping; they refer to this console, which must outlive the run.
  MapRunHooks hooks();
  /// Ends the progress bar, if any.
  void finish();

 private:
  std::string input_;
  bool quiet_;
  std::ostream& err_;
  std::optional<ProgressBar> bar_;  ///< made at the first progress report, when the total is known
  std::string last_topology_;
};

/// "gridtopo-map: N scans, M processed, U topology updates, read R s, mapping S s, total T s, peak RSS P MB, output
/// in DIR", newline.
std::string mapRunSummaryLine(const MapRunSummary& summary, const std::string& output);

}  // namespace gridtopo::mapping
