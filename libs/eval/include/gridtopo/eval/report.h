#pragma once
// Human summary and JSON of a relations-metric result.
#include <string>
#include <utility>
#include <vector>

#include "gridtopo/eval/relations_metric.h"

namespace gridtopo::eval {

/// Text block: translational m / m², rotational deg / deg², each "mean ± std (min .. max, n)".
std::string formatSummary(const RelationsResult& r);
/// JSON object with the four statistics, the endpoint counts and `info` (string key/values, e.g. inputs).
std::string formatJson(const RelationsResult& r, const std::vector<std::pair<std::string, std::string>>& info);
/// One line per relation: "t1 t2 translational_m rotational_deg gap1 gap2".
std::string formatErrors(const RelationsResult& r);

}  // namespace gridtopo::eval
