#pragma once
// The reports of the leave-one-map-out protocol (leave_one_map_out.h): the JSON of gridtopo-topology-eval, its
// Markdown table and its line per map.
#include <string>
#include <vector>

#include "gridtopo/eval/leave_one_map_out.h"

namespace gridtopo::eval {

/// 100 * v with one decimal ("87.3").
std::string percent(double v);

/// Mean and sample standard deviation (0 for fewer than two values).
double mean(const std::vector<double>& v);
double sampleStd(const std::vector<double>& v);

/// One line for a log: order, accuracy at every stage, oracle diagnostics, doorway recall before / after.
std::string mapScoreLine(const MapLabelScores& s, bool segment_vote, bool blob_vote);

/// The JSON report: mode, pooled label matrices and diagnostics, per-map scores, and (with segmentation) the
/// plain and furnished benchmark scores with their mean / std over maps.
std::string lomoJson(const LomoResult& r);

/// The Markdown table (measure | value) of doc/topology.md's results.
std::string lomoMarkdown(const LomoResult& r);

}  // namespace gridtopo::eval
