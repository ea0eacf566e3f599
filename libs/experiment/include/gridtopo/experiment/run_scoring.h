#pragma once
// What a finished gridtopo-slam run is scored on: its trajectory against the dataset's Freiburg relations
// (eval::evaluateRelations, gap correction by the raw log's odometry, as gridtopo-eval -r -l -t does), restricted
// to the relations whose two timestamps lie within the trajectory's time span (a run over the first n scans is
// scored on the relations of those scans), and its stats.txt (processed steps, resamplings, N_eff per step).
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gridtopo/eval/odometry_track.h"
#include "gridtopo/eval/relations.h"
#include "gridtopo/eval/relations_metric.h"
#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::experiment {

struct StepSummary {
  std::size_t steps = 0;        ///< processed scans (rows of stats.txt)
  std::size_t resamplings = 0;  ///< rows with resampled = 1
  std::vector<double> neff;     ///< N_eff after each step
};

/// Parses gridtopo-slam's stats.txt text (columns slam::kStatsColumns: step scan timestamp time_s neff resampled
/// ...); `name` names it in errors.
StepSummary summarizeSteps(const std::string& stats_text, const std::string& name);

/// The relations whose t1 and t2 both lie in [first, last] timestamp of `trajectory`.
std::vector<eval::Relation> relationsWithin(const std::vector<eval::Relation>& relations,
                                            const std::vector<TimedPose>& trajectory);

struct ErrorScores {
  std::size_t relations = 0;                ///< relations scored (0: no relations, no error figures)
  eval::ErrorStats translational, rotational;  ///< m, deg
  eval::RelationsSplit local, revisit;  ///< the same over local / revisit relations (RelationsMetricOptions' span)
};

/// Scores trajectories; keeps each dataset's relations and odometry after the first use.
class RunScorer {
 public:
  ErrorScores score(const std::vector<TimedPose>& trajectory, const std::string& log, const std::string& relations);

 private:
  struct Reference {
    std::vector<eval::Relation> relations;
    eval::OdometryTrack odometry;
  };
  std::map<std::string, std::shared_ptr<Reference>> cache_;
};

}  // namespace gridtopo::experiment
