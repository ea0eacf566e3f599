#pragma once
// One gridtopo-eval run: an estimate (a trajectory file, a CARMEN log with corrected poses, or the raw log's own
// odometry as the no-SLAM baseline) scored against ground-truth relations with the relations metric, the gaps
// carried over by the raw log's odometry (doc/evaluation.md).
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "gridtopo/core/output_set.h"
#include "gridtopo/eval/corrected_log.h"
#include "gridtopo/eval/loop_closure_summary.h"
#include "gridtopo/eval/relations.h"
#include "gridtopo/eval/relations_metric.h"
#include "gridtopo/io/carmen_log.h"

namespace gridtopo::eval {

struct RelationsRunSpec {
  std::string relations;      ///< ground-truth relations file (plain or .gz)
  std::string log;            ///< raw CARMEN log: odometry for the gap correction (empty: none)
  std::string trajectory;     ///< estimate: 'timestamp x y theta' lines ...
  std::string corrected_log;  ///< ... or a CARMEN log with corrected poses (needs `log`) ...
  bool baseline_odometry = false;  ///< ... or the raw log's odometry (needs `log`)
  RelationsMetricOptions metric;
  CorrectedLogOptions corrected;
  io::CarmenReadOptions read;  ///< how the CARMEN logs are read (skip_bad_lines)
  /// Score the relations inside the estimate's time span even when most relations fall outside it (a trajectory
  /// of part of the log; --partial). Without it such a run is refused.
  bool partial = false;
};

/// The [relations_metric] section of an INI file (config-ini/eval.ini); InputError naming the file and the key.
RelationsMetricOptions loadRelationsMetricIni(const std::string& path);
/// `gridtopo-eval --help-options`: every key of [relations_metric] with its default, range, unit and help.
std::string relationsMetricOptionsHelp();

/// gridtopo-eval's flags as given (empty / unset = not given).
struct RelationsFlags {
  std::string odometry;  ///< auto | odom | laser (overrides the INI)
  std::string gfs_match = "auto", gfs_pose = "robot";
  bool interpolate = false, interpolate_estimate = false;  ///< switch on (never off)
  std::optional<double> max_gap;
  std::optional<double> revisit_span;  ///< s, > 0: local / revisit split (overrides the INI's revisit_span)
};

/// Applies the flags over spec.metric (e.g. read by loadRelationsMetricIni) and spec.corrected. UsageError naming
/// the flag for an unknown word, a negative max gap or a revisit span not > 0.
void applyRelationsFlags(RelationsRunSpec& spec, const RelationsFlags& flags);

/// UsageError unless exactly one estimate is named, and the corrected log and the baseline have the raw log.
void checkRelationsRunSpec(const RelationsRunSpec& spec);

/// The run a command line names (gridtopo-eval): `spec`'s files checked (checkRelationsRunSpec), its metric options
/// from the INI `config` (loadRelationsMetricIni; the defaults without it), then the flags (applyRelationsFlags).
void configureRelationsRun(RelationsRunSpec& spec, const std::optional<std::string>& config,
                           const RelationsFlags& flags);

struct RelationsRun {
  std::size_t relation_count = 0;  ///< relations in the file
  std::size_t relations_scored = 0;     ///< inside the estimate's time span: scored
  std::size_t relations_corrected = 0;  ///< of those, with an endpoint carried over a gap by the log's odometry
  std::size_t relations_skipped = 0;    ///< outside the estimate's time span: not scored
  double estimate_first = 0.0, estimate_last = 0.0;  ///< the estimate's time span (s)
  /// What was scored, in order: relations, log, odometry (the source used), the estimate (trajectory / gfs + its
  /// time match and pose).
  std::vector<std::pair<std::string, std::string>> info;
  /// The yes/no options: odometry_interpolated, estimate_interpolated (JSON booleans).
  std::vector<std::pair<std::string, bool>> flags;
  /// The numbers of the run, in order: max_time_gap_s (the option), estimated_poses, relations_total,
  /// relations_scored, relations_corrected, relations_skipped (JSON numbers).
  std::vector<std::pair<std::string, double>> numbers;
  RelationsResult result;
  /// What the loop closure did in the run that made the trajectory (its stats.txt beside it), when there is one;
  /// its counts are also in `numbers` as "loop_closure_KEY".
  std::optional<LoopClosureSummary> loop_closure;
};

/// Reads the relations, the raw log (its ODOM lines or laser-line odometry as spec.metric.odometry says; skipped
/// malformed lines are reported to `log`) and the estimate, then evaluateRelations on the relations whose two
/// times lie in the estimate's time span (± max_time_gap); the others are skipped and counted. InputError for an
/// empty relations file, an estimate without poses, --odometry odom on a log without ODOM lines, relations that do
/// not overlap the estimate in time, most relations outside it (unless spec.partial), or a raw log whose times do
/// not cover the estimate's (a log of another run).
RelationsRun runRelations(const RelationsRunSpec& spec, std::ostream& log);

/// What gridtopo-eval prints on stdout: the relations line, the info lines and formatSummary.
std::string relationsRunText(const RelationsRun& run);

/// Stages the JSON (formatJson with the run's info) and the per-relation errors (formatErrors) in `outputs`; an
/// empty path writes nothing.
void stageRelationsOutputs(OutputSet& outputs, const RelationsRun& run, const std::string& json_path,
                           const std::string& errors_path);

/// Writes the JSON and the errors file of stageRelationsOutputs, both or neither.
void writeRelationsOutputs(const RelationsRun& run, const std::string& json_path, const std::string& errors_path);

/// The warnings of a run (relation endpoints left uncorrected, a relation far from every estimated pose), each a
/// line with its newline; "" when there are none.
std::string relationsRunWarnings(const RelationsRun& run);

}  // namespace gridtopo::eval
