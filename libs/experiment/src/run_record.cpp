#include "gridtopo/experiment/run_record.h"

#include <unistd.h>

#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <type_traits>
#include <vector>

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

// The record's fields in the order of its JSON: one table for writing and reading. Doubles are written as null
// when not finite and read back as NaN when absent or null; other fields are required.
template <class R, class F>
void forEachHeadField(R& r, F&& f) {
  f("index", r.index);
  f("id", r.id);
  f("label", r.label);
  f("status", r.status);
  f("error", r.error);
  f("exit_code", r.exit_code);
  f("signal", r.signal);
  f("dataset", r.dataset);
  f("log", r.log);
  f("relations", r.relations);
  f("max_scans", r.max_scans);
}
template <class R, class F>
void forEachSlamScore(R& r, F&& f) {
  f("relations_scored", r.relations_scored);
  f("trans_mean_m", r.trans_mean);
  f("trans_std_m", r.trans_std);
  f("trans_max_m", r.trans_max);
  f("rot_mean_deg", r.rot_mean);
  f("rot_std_deg", r.rot_std);
  f("rot_max_deg", r.rot_max);
  f("trans_local_mean_m", r.trans_local_mean);
  f("trans_revisit_mean_m", r.trans_revisit_mean);
  f("steps", r.steps);
  f("resamplings", r.resamplings);
}
template <class R, class F>
void forEachTopologyScore(R& r, F&& f) {
  f("graph_nodes", r.graph_nodes);
  f("graph_edges", r.graph_edges);
  f("label_accuracy", r.label_accuracy);
  f("recall_room", r.recall_room);
  f("recall_corridor", r.recall_corridor);
  f("recall_doorway", r.recall_doorway);
  f("seg_recall", r.seg_recall);
  f("seg_precision", r.seg_precision);
  f("graph_attached", r.graph_attached);
  f("graph_loops_closed", r.graph_loops_closed);
  f("graph_plan_loops", r.graph_plan_loops);
}
template <class R, class F>
void forEachTailField(R& r, F&& f) {
  f("wall_s", r.wall_s);
  f("cpu_s", r.cpu_s);
  f("peak_rss_mb", r.peak_rss_mb);
  f("commit", r.commit);
  f("host", r.host);
  f("start_time", r.start_time);
  f("dir", r.dir);
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
  auto put = [&](const char* key, const auto& value) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, double>) j[key] = number(value);
    else j[key] = value;
  };
  auto object = [](const auto& pairs) {
    json o = json::object();
    for (const auto& [k, v] : pairs) o[k] = v;
    return o;
  };
  forEachHeadField(r, put);
  j["params"] = object(r.params);
  j["options"] = object(r.options);
  forEachSlamScore(r, put);
  if (r.topology) {  // only in topology runs' records: SLAM-only records stay as they were
    j["topology_options"] = object(r.topology_options);
    forEachTopologyScore(r, put);
  }
  forEachTailField(r, put);
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
    auto get = [&](const char* key, auto& value) {
      using T = std::decay_t<decltype(value)>;
      if constexpr (std::is_same_v<T, double>) value = numberOf(j, key);
      else value = j.at(key).template get<T>();
    };
    auto pairs = [&](const char* key, std::vector<std::pair<std::string, std::string>>& out) {
      for (const auto& [k, v] : j.at(key).items()) out.emplace_back(k, v.get<std::string>());
    };
    forEachHeadField(r, get);
    pairs("params", r.params);
    pairs("options", r.options);
    forEachSlamScore(r, get);
    r.topology = j.contains("topology_options");
    if (r.topology) {
      pairs("topology_options", r.topology_options);
      forEachTopologyScore(r, get);
    }
    forEachTailField(r, get);
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
