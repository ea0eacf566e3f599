#pragma once
// What is kept of one run: RUN/result.json, written atomically when the run ends (ok, failed or crashed). A run
// whose result.json says ok under the same id is not run again; an interrupted run has none and runs again.
#include <string>
#include <utility>
#include <vector>

#include "gridtopo/experiment/run_plan.h"

namespace gridtopo::experiment {

struct RunRecord {
  std::size_t index = 0;
  std::string id, label, dir;
  std::string dataset, log, relations;
  long max_scans = -1;
  Assignment params;                                     ///< the swept keys
  std::vector<std::pair<std::string, std::string>> options;  ///< every [slam] option of the run
  std::string status;  ///< "ok", "failed" (non-zero exit or unscorable output) or "crashed" (killed by a signal)
  std::string error;   ///< the reason when not ok
  int exit_code = 0, signal = 0;
  // Metrics (NaN when there are none: failed run or no relations).
  std::size_t relations_scored = 0;
  double trans_mean = 0, trans_std = 0, trans_max = 0;  ///< m
  double rot_mean = 0, rot_std = 0, rot_max = 0;        ///< deg
  /// m: the mean translational error over the local relations (|t2 - t1| <= 50 s) and over the revisits (> 50 s);
  /// NaN when there are none (also in records written before these fields existed).
  double trans_local_mean = 0, trans_revisit_mean = 0;
  std::size_t steps = 0, resamplings = 0;
  // Topology runs (topology = true): the options (section.key) and the scores (topology_scoring.h; NaN without a
  // plan, or when the run failed).
  bool topology = false;
  std::vector<std::pair<std::string, std::string>> topology_options;
  std::size_t graph_nodes = 0, graph_edges = 0;
  double label_accuracy = 0, recall_room = 0, recall_corridor = 0, recall_doorway = 0;  ///< fractions of cells
  double seg_recall = 0, seg_precision = 0;                                             ///< room segmentation
  double graph_attached = 0;                   ///< fraction of plan rooms with one room node attached by a doorway
  double graph_loops_closed = 0, graph_plan_loops = 0;  ///< plan corridor loops closed by corridor node cycles
  double wall_s = 0, cpu_s = 0, peak_rss_mb = 0;
  std::string commit, host, start_time;

  bool ok() const { return status == "ok"; }
  bool hasErrors() const { return ok() && relations_scored > 0; }
  bool hasPlanScores() const { return ok() && topology && label_accuracy == label_accuracy; }
};

/// A record with the run's identity and parameters filled in (status empty).
RunRecord recordOf(const PlannedRun& run);

std::string toJson(const RunRecord& r);  ///< one line, no newline
RunRecord recordFromJson(const std::string& text, const std::string& name);  ///< InputError naming `name`

/// RUN/result.json of `run` if it exists and belongs to the same id; false otherwise (also for an unreadable file).
bool loadRecord(const PlannedRun& run, RunRecord& out);
void saveRecord(const RunRecord& r);  ///< atomically, RUN/result.json

/// The commit of the source tree (short hash, "-dirty" when tracked files changed), or "unknown".
std::string sourceCommit();
std::string hostName();
std::string utcNow();  ///< ISO 8601, seconds

}  // namespace gridtopo::experiment
