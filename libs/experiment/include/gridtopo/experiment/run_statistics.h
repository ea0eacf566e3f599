#pragma once
// Statistics over the runs of one group (the runs that differ only by their seed): mean, sample standard deviation,
// median, min and max of a metric, and which runs belong together.
#include <cstddef>
#include <string>
#include <vector>

#include "gridtopo/experiment/run_record.h"

namespace gridtopo::experiment {

struct Spread {
  std::size_t count = 0;
  double mean = 0, std = 0, median = 0, min = 0, max = 0;  ///< NaN when count = 0; std = 0 when count < 2
  static Spread of(std::vector<double> values);             ///< NaN values are left out
};

/// 1 / 0 when the run has error figures (the success metric against the threshold), -1 when it has none.
int successOf(const ExperimentSpec& spec, const RunRecord& r);

struct RunGroup {
  Assignment key;                   ///< the group's values of the grouping keys
  std::vector<const RunRecord*> runs;
};

/// Groups `records` by their values of `keys` (in order of first appearance).
std::vector<RunGroup> groupRuns(const std::vector<RunRecord>& records, const std::vector<std::string>& keys);

/// The varied keys but `except`.
std::vector<std::string> keysBut(const std::vector<std::string>& keys, const std::vector<std::string>& except);

}  // namespace gridtopo::experiment
