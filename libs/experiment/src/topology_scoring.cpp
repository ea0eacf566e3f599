#include "gridtopo/experiment/topology_scoring.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "gridtopo/core/error.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace gridtopo::experiment {
namespace {

json readJson(const fs::path& p) {
  std::ifstream f(p);
  if (!f) throw InputError(p.string(), "missing: the topology run wrote no such file");
  try {
    return json::parse(f);
  } catch (const json::exception& e) {
    throw InputError(p.string(), 0, "", std::string("not JSON: ") + e.what());
  }
}

}  // namespace

void scoreTopology(const std::string& topology_dir, bool with_plan, RunRecord& r) {
  r.label_accuracy = r.recall_room = r.recall_corridor = r.recall_doorway = NAN;
  r.seg_recall = r.seg_precision = r.graph_attached = r.graph_loops_closed = r.graph_plan_loops = NAN;
  const fs::path graph = fs::path(topology_dir) / "topology.json";
  const json g = readJson(graph);
  if (!g.contains("nodes") || !g.contains("edges") || !g["nodes"].is_array() || !g["edges"].is_array())
    throw InputError(graph.string(), 0, "nodes", "no nodes / edges arrays");
  r.graph_nodes = g["nodes"].size();
  r.graph_edges = g["edges"].size();
  if (!with_plan) return;
  const fs::path compare = fs::path(topology_dir) / "compare.json";
  const json c = readJson(compare);
  std::string at = "labels";
  try {
    const json& labels = c.at("labels");
    r.label_accuracy = labels.at("accuracy").get<double>();
    r.recall_room = labels.at("recall").at(0).get<double>();  // classes: room, corridor, doorway
    r.recall_corridor = labels.at("recall").at(1).get<double>();
    r.recall_doorway = labels.at("recall").at(2).get<double>();
    at = "segmentation";
    r.seg_recall = c.at(at).at("recall").get<double>();
    r.seg_precision = c.at(at).at("precision").get<double>();
    at = "graph";
    r.graph_attached = c.at(at).at("attached_fraction").get<double>();
    r.graph_loops_closed = c.at(at).at("loops_closed").get<double>();
    r.graph_plan_loops = c.at(at).at("plan_loops").get<double>();
  } catch (const json::exception& e) {
    throw InputError(compare.string(), 0, at, std::string("incomplete scores: ") + e.what());
  }
}

}  // namespace gridtopo::experiment
