#include "gridtopo/mapping/map_run_console.h"

#include <cstdio>
#include <utility>

#include "gridtopo/core/process_memory.h"

namespace gridtopo::mapping {

std::string topologyCounts(const topology::TopologicalGraph& graph) {
  int counts[3] = {0, 0, 0};
  for (const auto& n : graph.nodes) counts[n.label]++;
  return std::to_string(counts[0]) + " rooms, " + std::to_string(counts[1]) + " corridors, " +
         std::to_string(counts[2]) + " doorways, " + std::to_string(graph.edges.size()) + " edges";
}

MapRunConsole::MapRunConsole(std::string input, bool quiet, std::ostream& err)
    : input_(std::move(input)), quiet_(quiet), err_(err) {}

MapRunHooks MapRunConsole::hooks() {
  MapRunHooks hooks;
  hooks.warning = [this](const std::string& w) { err_ << "gridtopo-map: warning: " << input_ << ": " << w << "\n"; };
  if (quiet_) return hooks;
  hooks.note = [this](const std::string& n) { err_ << "gridtopo-map: note: " << input_ << ": " << n << "\n"; };
  hooks.progress = [this](std::size_t fed, std::size_t total) {
    if (!bar_) bar_.emplace(total, "map", "scans");
    bar_->update(fed, last_topology_);
  };
  hooks.topologyUpdated = [this](const MapTopology& t) {
    last_topology_ = topologyCounts(t.graph());
    if (!bar_ || !bar_->enabled())
      err_ << "gridtopo-map: topology at " << t.map_size << " processed scans: " << last_topology_ << "\n";
  };
  return hooks;
}

void MapRunConsole::finish() {
  if (bar_) bar_->finish();
}

std::string mapRunSummaryLine(const MapRunSummary& s, const std::string& output) {
  char line[512];
  std::snprintf(line, sizeof line,
                "gridtopo-map: %zu scans, %zu processed, %zu topology updates, read %.2f s, mapping %.2f s, total "
                "%.2f s, peak RSS %zu MB, output in ",
                s.scans, s.steps, s.topology_updates, s.seconds_read, s.seconds_mapping, s.seconds_total,
                processMemory().peak_kb / 1024);
  return line + output + "\n";
}

}  // namespace gridtopo::mapping
