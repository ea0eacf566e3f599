// What gridtopo-map says while it runs (mapping/map_run_console.h).
#include <gtest/gtest.h>

#include <sstream>

#include "gridtopo/mapping/map_run_console.h"

using namespace gridtopo;

namespace {
mapping::MapTopology topologyOf(std::vector<int> labels, std::size_t edges, unsigned map_size) {
  mapping::MapTopology t;
  for (int l : labels) {
    topology::GraphNode n;
    n.label = l;
    t.topo.graph.nodes.push_back(n);
  }
  t.topo.graph.edges.resize(edges);
  t.map_size = map_size;
  return t;
}
}  // namespace

TEST(MapRunConsole, CountsTheGraphsNodesByLabelAndItsEdges) {
  EXPECT_EQ(mapping::topologyCounts(topologyOf({0, 1, 2, 0, 0, 2}, 5, 1).graph()),
            "3 rooms, 1 corridors, 2 doorways, 5 edges");
  EXPECT_EQ(mapping::topologyCounts(topology::TopologicalGraph{}), "0 rooms, 0 corridors, 0 doorways, 0 edges");
}

TEST(MapRunConsole, SaysWarningsAlwaysAndTheRestUnlessQuiet) {
  std::ostringstream loud_text, quiet_text;
  mapping::MapRunConsole loud("log.clf", false, loud_text), quiet("log.clf", true, quiet_text);
  const auto l = loud.hooks(), q = quiet.hooks();
  l.warning("odd line"), q.warning("odd line");
  EXPECT_EQ(quiet_text.str(), "gridtopo-map: warning: log.clf: odd line\n");
  EXPECT_FALSE(q.note || q.progress || q.topologyUpdated);
  l.note("CARMEN new format");
  // No bar yet (it comes with the first progress report): a topology update is a line of its own.
  l.topologyUpdated(topologyOf({0, 1}, 1, 120));
  loud.finish();
  EXPECT_EQ(loud_text.str(),
            "gridtopo-map: warning: log.clf: odd line\n"
            "gridtopo-map: note: log.clf: CARMEN new format\n"
            "gridtopo-map: topology at 120 processed scans: 1 rooms, 1 corridors, 0 doorways, 1 edges\n");
}

TEST(MapRunConsole, TheSummaryLine) {
  mapping::MapRunSummary s;
  s.scans = 300, s.steps = 43, s.topology_updates = 2;
  s.seconds_read = 0.404, s.seconds_mapping = 1.5, s.seconds_total = 2;
  const std::string line = mapping::mapRunSummaryLine(s, "/tmp/out");
  EXPECT_EQ(line.rfind("gridtopo-map: 300 scans, 43 processed, 2 topology updates, read 0.40 s, mapping 1.50 s, "
                       "total 2.00 s, peak RSS ", 0), 0u) << line;
  EXPECT_EQ(line.substr(line.size() - 24), " MB, output in /tmp/out\n");
}
