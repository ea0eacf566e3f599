#pragma once
// Human summary and JSON of a relations-metric result.
#include <string>
#include <utility>
#include <vector>

#include "gridtopo/eval/relations_metric.h"

namespace gridtopo::eval {

/// Text block: translational m / m², rotational deg / deg², each "mean ± std (min .. max, n)"; the endpoint counts;
/// last the split "local (|t2-t1| <= 50 s): 0.0589 m (n=1773), 2.47 deg; revisits (> 50 s): 0.0631 m (n=1211),
/// 2.27 deg" (means; "none (n=0)" for an empty side).
std::string formatSummary(const RelationsResult& r);
/// JSON object with `info` (string key/values, e.g. inputs), then `numbers` (key/values written as JSON numbers,
/// null when not finite), the four statistics, the endpoint counts, then "revisit_span_s" and the split "local" /
/// "revisit" ({"count", "translational_m", "rotational_deg"}; an empty side's statistics are null), last the
/// largest time gap met ("largest_time_gap_s"). `flags` (yes/no options) follow `info` as JSON booleans. Every key
/// once: std::invalid_argument if `info`, `flags` or `numbers` repeat a key or use one of the result's.
std::string formatJson(const RelationsResult& r, const std::vector<std::pair<std::string, std::string>>& info,
                       const std::vector<std::pair<std::string, double>>& numbers = {},
                       const std::vector<std::pair<std::string, bool>>& flags = {});
/// One line per relation: "t1 t2 translational_m rotational_deg gap1 gap2".
std::string formatErrors(const RelationsResult& r);
/// `s` as a JSON string literal: quoted, with quotes, backslashes and control characters escaped.
std::string jsonString(const std::string& s);

}  // namespace gridtopo::eval
