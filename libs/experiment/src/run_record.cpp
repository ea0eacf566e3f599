#include "gridtopo/experiment/run_record.h"

#include <unistd.h>

#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/core/ini_file.h"

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace gridtopo::experiment {
namespace {

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double numberOf(const json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

std::string firstLineOf(const std::string& cmd) {
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return "";
  char buf[256];
  std::string s;
  if (std::fgets(buf, sizeof buf, p)) s = buf;
  ::pclose(p);
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

}  // namespace

RunRecord recordOf(const PlannedRun& run) {
  RunRecord r;
  r.index = run.index;
  r.id = run.id;
  r.label = run.label;
  r.dir = run.dir;
  r.dataset = run.dataset;
  r.log = run.log;
  r.relations = run.relations;
  r.max_scans = run.max_scans;
  r.params = run.params;
  const IniFile doc = IniFile::parse(run.options_ini, "<options>");
  for (const auto& key : doc.keys("slam")) r.options.emplace_back(key, *doc.value("slam", key));
  r.topology = run.topology;
  if (run.topology) {
    const IniFile t = IniFile::parse(run.topology_options_ini, "<topology options>");
    for (const auto& sec : t.sections())
      for (const auto& key : t.keys(sec)) r.topology_options.emplace_back(sec + "." + key, *t.value(sec, key));
  }
  return r;
}

std::string toJson(const RunRecord& r) {
  json j;
  j["index"] = r.index;
  j["id"] = r.id;
  j["label"] = r.label;
  j["status"] = r.status;
  j["error"] = r.error;
  j["exit_code"] = r.exit_code;
  j["signal"] = r.signal;
  j["dataset"] = r.dataset;
  j["log"] = r.log;
  j["relations"] = r.relations;
  j["max_scans"] = r.max_scans;
  json params = json::object();
  for (const auto& [k, v] : r.params) params[k] = v;
  j["params"] = params;
  json options = json::object();
  for (const auto& [k, v] : r.options) options[k] = v;
  j["options"] = options;
  j["relations_scored"] = r.relations_scored;
  j["trans_mean_m"] = number(r.trans_mean);
  j["trans_std_m"] = number(r.trans_std);
  j["trans_max_m"] = number(r.trans_max);
  j["rot_mean_deg"] = number(r.rot_mean);
  j["rot_std_deg"] = number(r.rot_std);
  j["rot_max_deg"] = number(r.rot_max);
  j["steps"] = r.steps;
  j["resamplings"] = r.resamplings;
  if (r.topology) {  // only in topology runs' records: SLAM-only records stay as they were
    json topo = json::object();
    for (const auto& [k, v] : r.topology_options) topo[k] = v;
    j["topology_options"] = topo;
    j["graph_nodes"] = r.graph_nodes;
    j["graph_edges"] = r.graph_edges;
    j["label_accuracy"] = number(r.label_accuracy);
    j["recall_room"] = number(r.recall_room);
    j["recall_corridor"] = number(r.recall_corridor);
    j["recall_doorway"] = number(r.recall_doorway);
    j["seg_recall"] = number(r.seg_recall);
    j["seg_precision"] = number(r.seg_precision);
    j["graph_attached"] = number(r.graph_attached);
    j["graph_loops_closed"] = number(r.graph_loops_closed);
    j["graph_plan_loops"] = number(r.graph_plan_loops);
  }
  j["wall_s"] = number(r.wall_s);
  j["cpu_s"] = number(r.cpu_s);
  j["peak_rss_mb"] = number(r.peak_rss_mb);
  j["commit"] = r.commit;
  j["host"] = r.host;
  j["start_time"] = r.start_time;
  j["dir"] = r.dir;
  return j.dump();
}

RunRecord recordFromJson(const std::string& text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(name, 0, "", std::string("not a run record: ") + e.what());
  }
  RunRecord r;
  try {
    r.index = j.at("index").get<std::size_t>();
    r.id = j.at("id").get<std::string>();
    r.label = j.at("label").get<std::string>();
    r.status = j.at("status").get<std::string>();
    r.error = j.at("error").get<std::string>();
    r.exit_code = j.at("exit_code").get<int>();
    r.signal = j.at("signal").get<int>();
    r.dataset = j.at("dataset").get<std::string>();
    r.log = j.at("log").get<std::string>();
    r.relations = j.at("relations").get<std::string>();
    r.max_scans = j.at("max_scans").get<long>();
    for (const auto& [k, v] : j.at("params").items()) r.params.emplace_back(k, v.get<std::string>());
    for (const auto& [k, v] : j.at("options").items()) r.options.emplace_back(k, v.get<std::string>());
    r.relations_scored = j.at("relations_scored").get<std::size_t>();
    r.trans_mean = numberOf(j, "trans_mean_m");
    r.trans_std = numberOf(j, "trans_std_m");
    r.trans_max = numberOf(j, "trans_max_m");
    r.rot_mean = numberOf(j, "rot_mean_deg");
    r.rot_std = numberOf(j, "rot_std_deg");
    r.rot_max = numberOf(j, "rot_max_deg");
    r.steps = j.at("steps").get<std::size_t>();
    r.resamplings = j.at("resamplings").get<std::size_t>();
    r.topology = j.contains("topology_options");
    if (r.topology) {
      for (const auto& [k, v] : j.at("topology_options").items()) r.topology_options.emplace_back(k, v.get<std::string>());
      r.graph_nodes = j.at("graph_nodes").get<std::size_t>();
      r.graph_edges = j.at("graph_edges").get<std::size_t>();
      r.label_accuracy = numberOf(j, "label_accuracy");
      r.recall_room = numberOf(j, "recall_room");
      r.recall_corridor = numberOf(j, "recall_corridor");
      r.recall_doorway = numberOf(j, "recall_doorway");
      r.seg_recall = numberOf(j, "seg_recall");
      r.seg_precision = numberOf(j, "seg_precision");
      r.graph_attached = numberOf(j, "graph_attached");
      r.graph_loops_closed = numberOf(j, "graph_loops_closed");
      r.graph_plan_loops = numberOf(j, "graph_plan_loops");
    }
    r.wall_s = numberOf(j, "wall_s");
    r.cpu_s = numberOf(j, "cpu_s");
    r.peak_rss_mb = numberOf(j, "peak_rss_mb");
    r.commit = j.at("commit").get<std::string>();
    r.host = j.at("host").get<std::string>();
    r.start_time = j.at("start_time").get<std::string>();
    r.dir = j.at("dir").get<std::string>();
  } catch (const json::exception& e) {
    throw InputError(name, 0, "", std::string("incomplete run record: ") + e.what());
  }
  return r;
}

bool loadRecord(const PlannedRun& run, RunRecord& out) {
  const fs::path p = fs::path(run.dir) / "result.json";
  std::ifstream f(p);
  if (!f) return false;
  std::ostringstream ss;
  ss << f.rdbuf();
  try {
    RunRecord r = recordFromJson(ss.str(), p.string());
    if (r.id != run.id) return false;
    // Same id, same options and input contents: the record describes this plan's run, wherever the experiment,
    // its inputs or its results folder were when it ran, and at whichever position of an edited sweep.
    r.index = run.index;
    r.params = run.params;
    r.label = run.label;
    r.dir = run.dir;
    r.dataset = run.dataset;
    r.log = run.log;
    r.relations = run.relations;
    out = std::move(r);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

void saveRecord(const RunRecord& r) {
  writeTextFileAtomically((fs::path(r.dir) / "result.json").string(), toJson(r) + "\n");
}

std::string sourceCommit() {
#ifdef GRIDTOPO_SOURCE_DIR
  const std::string dir = GRIDTOPO_SOURCE_DIR;
  std::string c = firstLineOf("git -C '" + dir + "' rev-parse --short=12 HEAD 2>/dev/null");
  if (c.empty()) return "unknown";
  if (!firstLineOf("git -C '" + dir + "' status --porcelain --untracked-files=no 2>/dev/null").empty()) c += "-dirty";
  return c;
#else
  return "unknown";
#endif
}

std::string hostName() {
  char buf[256] = {0};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace gridtopo::experiment
