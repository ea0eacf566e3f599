#pragma once
// What a finished topology run is scored on: the graph gridtopo-topology wrote (RUN/topology/topology.json: its
// nodes and edges) and, when the dataset has a labelled plan, gridtopo-topology-compare's scores against it
// (RUN/topology/compare.json: cell-label accuracy, per-class recall, room-segmentation recall and precision, the
// graph against the plan's rooms and corridor loops).
#include <string>

#include "gridtopo/experiment/run_record.h"

namespace gridtopo::experiment {

/// Fills the topology metrics of `r` from the files in `topology_dir` (compare.json only when `with_plan`); the
/// plan scores stay NaN without a plan. InputError naming the file when one is missing or incomplete.
void scoreTopology(const std::string& topology_dir, bool with_plan, RunRecord& r);

}  // namespace gridtopo::experiment
