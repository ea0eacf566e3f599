#pragma once
// The experiment's tables: results.csv and results.jsonl (one row per recorded run: every parameter, every metric,
// the success flag, times, memory, commit, host, start time) and summary.md (runs grouped by every varied key but
// the seed: mean, std, median, min, max of the errors, success rate, times).
#include <iosfwd>
#include <string>
#include <vector>

#include "gridtopo/experiment/run_record.h"

namespace gridtopo::experiment {

/// The CSV's columns, in order: index id label status dataset log relations max_scans, every [slam] option key,
/// relations_scored trans_mean_m trans_std_m trans_max_m rot_mean_deg rot_std_deg rot_max_deg trans_local_mean_m
/// trans_revisit_mean_m success steps resamplings wall_s cpu_s peak_rss_mb commit host start_time error dir.
std::vector<std::string> resultsColumns(const ExperimentPlan& plan);

std::string resultsCsv(const ExperimentPlan& plan, const std::vector<RunRecord>& records);
std::string resultsJsonl(const ExperimentPlan& plan, const std::vector<RunRecord>& records);
std::string summaryMarkdown(const ExperimentPlan& plan, const std::vector<RunRecord>& records);

/// Every planned run's record that exists (ok, failed or crashed), in plan order.
std::vector<RunRecord> collectRecords(const ExperimentPlan& plan);

/// Writes results.csv, results.jsonl and summary.md into plan.output, all or nothing.
void writeResults(const ExperimentPlan& plan, const std::vector<RunRecord>& records);

/// collectRecords, writeResults and drawPlots, with a line to `log` (and the plots' notes). True when every
/// recorded run is ok.
bool writeTablesAndPlots(const ExperimentPlan& plan, std::ostream& log);

}  // namespace gridtopo::experiment
