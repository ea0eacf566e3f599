#include "gridtopo/experiment/results_writer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "gridtopo/core/output_set.h"
#include "gridtopo/experiment/plots.h"
#include "gridtopo/experiment/run_statistics.h"
#include "gridtopo/io/trajectory_io.h"

namespace fs = std::filesystem;

namespace gridtopo::experiment {
namespace {

std::string num(double v) { return std::isfinite(v) ? io::formatDouble(v) : std::string(); }

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "–";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string optionOf(const std::vector<std::pair<std::string, std::string>>& options, const std::string& key) {
  for (const auto& [k, v] : options)
    if (k == key) return v;
  return "";
}

/// The topology metric columns (only in experiments with topology runs).
constexpr const char* kTopologyColumns[] = {"graph_nodes",     "graph_edges",   "label_accuracy", "recall_room",
                                            "recall_corridor", "recall_doorway", "seg_recall",     "seg_precision",
                                            "graph_attached",  "graph_loops_closed", "graph_plan_loops"};

std::vector<std::string> topologyFields(const RunRecord& r) {
  if (!r.topology || !r.ok()) return std::vector<std::string>(std::size(kTopologyColumns));
  return {std::to_string(r.graph_nodes), std::to_string(r.graph_edges), num(r.label_accuracy), num(r.recall_room),
          num(r.recall_corridor), num(r.recall_doorway), num(r.seg_recall), num(r.seg_precision),
          num(r.graph_attached), num(r.graph_loops_closed), num(r.graph_plan_loops)};
}

}  // namespace

std::vector<std::string> resultsColumns(const ExperimentPlan& plan) {
  std::vector<std::string> c = {"index", "id", "label", "status", "dataset", "log", "relations", "max_scans"};
  c.insert(c.end(), plan.slam_keys.begin(), plan.slam_keys.end());
  c.insert(c.end(), plan.topology_keys.begin(), plan.topology_keys.end());
  for (const char* k : {"relations_scored", "trans_mean_m", "trans_std_m", "trans_max_m", "rot_mean_deg", "rot_std_deg",
                        "rot_max_deg", "trans_local_mean_m", "trans_revisit_mean_m", "success", "steps", "resamplings"})
    c.push_back(k);
  if (!plan.topology_keys.empty()) c.insert(c.end(), std::begin(kTopologyColumns), std::end(kTopologyColumns));
  for (const char* k : {"wall_s", "cpu_s", "peak_rss_mb", "commit", "host", "start_time", "error", "dir"}) c.push_back(k);
  return c;
}

std::string resultsCsv(const ExperimentPlan& plan, const std::vector<RunRecord>& records) {
  std::ostringstream o;
  const auto cols = resultsColumns(plan);
  for (std::size_t i = 0; i < cols.size(); ++i) o << (i ? "," : "") << cols[i];
  o << "\n";
  for (const auto& r : records) {
    const int success = successOf(plan.spec, r);
    std::vector<std::string> f = {std::to_string(r.index), r.id, r.label, r.status, r.dataset, r.log, r.relations,
                                  r.max_scans > 0 ? std::to_string(r.max_scans) : ""};
    for (const auto& k : plan.slam_keys) f.push_back(optionOf(r.options, k));
    for (const auto& k : plan.topology_keys) f.push_back(optionOf(r.topology_options, k));
    for (const auto& v : {std::to_string(r.relations_scored), num(r.trans_mean), num(r.trans_std), num(r.trans_max),
                          num(r.rot_mean), num(r.rot_std), num(r.rot_max), num(r.trans_local_mean),
                          num(r.trans_revisit_mean),
                          success < 0 ? std::string() : std::to_string(success), std::to_string(r.steps),
                          std::to_string(r.resamplings)})
      f.push_back(v);
    if (!plan.topology_keys.empty())
      for (const auto& v : topologyFields(r)) f.push_back(v);
    for (const auto& v : {num(r.wall_s), num(r.cpu_s), num(r.peak_rss_mb), r.commit, r.host, r.start_time, r.error,
                          r.dir})
      f.push_back(v);
    for (std::size_t i = 0; i < f.size(); ++i) o << (i ? "," : "") << csvField(f[i]);
    o << "\n";
  }
  return o.str();
}

std::string resultsJsonl(const ExperimentPlan& plan, const std::vector<RunRecord>& records) {
  std::ostringstream o;
  for (const auto& r : records) {
    auto j = nlohmann::ordered_json::parse(toJson(r));
    const int success = successOf(plan.spec, r);
    j["success"] = success < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(success == 1);
    j["success_metric"] = toString(plan.spec.success_metric);
    j["success_threshold"] = plan.spec.success_threshold;
    o << j.dump() << "\n";
  }
  return o.str();
}

std::string summaryMarkdown(const ExperimentPlan& plan, const std::vector<RunRecord>& records) {
  std::ostringstream o;
  const auto keys = keysBut(plan.varied_keys, {"seed"});
  std::size_t ok = 0, failed = 0;
  for (const auto& r : records) (r.ok() ? ok : failed) += 1;
  o << "# Experiment " << plan.spec.name << "\n\n";
  if (!plan.spec.description.empty()) o << plan.spec.description << "\n\n";
  o << "From `" << plan.spec.path << "`: " << plan.runs.size() << " runs planned, " << records.size()
    << " recorded (" << ok << " ok, " << failed << " failed or crashed)";
  if (records.size() < plan.runs.size()) o << ", " << plan.runs.size() - records.size() << " not run yet";
  o << ". Runs are grouped by " << (keys.empty() ? std::string("nothing") : std::string());
  for (std::size_t i = 0; i < keys.size(); ++i) o << (i ? ", " : "") << "`" << keys[i] << "`";
  o << "; each line is over its seeds. Error: the Freiburg relations metric (Kümmerle et al. 2009) of each run's "
       "trajectory, mean over its relations; the columns give mean, std, median, min and max of that mean over the "
       "group's runs. Success: `"
    << toString(plan.spec.success_metric) << "` <= " << plan.spec.success_threshold
    << (plan.spec.success_metric == SuccessMetric::TransMean || plan.spec.success_metric == SuccessMetric::TransMax
            ? " m"
            : " deg")
    ;
  const bool topo = !plan.topology_keys.empty();
  o << (topo ? ". Times are per run (wall and CPU of its processes), peak RSS their maximum."
             : ". Times are per run (wall and CPU of the gridtopo-slam process), peak RSS its maximum.");
  if (topo)
    o << " Topology (means over the group's runs): graph nodes and edges; against the dataset's labelled plan "
         "(gridtopo-topology-compare) the cell-label accuracy, the doorway recall, the room-segmentation recall and "
         "precision, and the fraction of plan rooms with one room node attached through a doorway.";
  o << "\n\n|";
  for (const auto& k : keys) o << " " << k << " |";
  o << " runs | failed | trans mean (m) | trans std | trans median | trans min | trans max | rot mean (deg) | "
       "success | wall (s) | CPU (s) | peak RSS (MB) | resamplings |";
  if (topo) o << " nodes | edges | label accuracy | doorway recall | seg recall | seg precision | rooms attached |";
  o << "\n|";
  for (std::size_t i = 0; i < keys.size() + 13 + (topo ? 7 : 0); ++i) o << "---|";
  o << "\n";
  for (const auto& g : groupRuns(records, keys)) {
    std::vector<double> tm, rm, wall, cpu, rss, res, nodes, edges, acc, door, segr, segp, att;
    std::size_t nf = 0, scored = 0, succ = 0;
    for (const RunRecord* r : g.runs) {
      if (!r->ok()) ++nf;
      const int s = successOf(plan.spec, *r);
      if (s >= 0) ++scored, succ += s == 1;
      if (!r->ok()) continue;
      tm.push_back(r->hasErrors() ? r->trans_mean : NAN);
      rm.push_back(r->hasErrors() ? r->rot_mean : NAN);
      wall.push_back(r->wall_s);
      cpu.push_back(r->cpu_s);
      rss.push_back(r->peak_rss_mb);
      if (r->steps > 0 || !r->topology) res.push_back(static_cast<double>(r->resamplings));  // not for a map alone
      if (r->topology) {
        nodes.push_back(static_cast<double>(r->graph_nodes));
        edges.push_back(static_cast<double>(r->graph_edges));
        acc.push_back(r->label_accuracy);
        door.push_back(r->recall_doorway);
        segr.push_back(r->seg_recall);
        segp.push_back(r->seg_precision);
        att.push_back(r->graph_attached);
      }
    }
    const Spread t = Spread::of(tm);
    o << "|";
    for (const auto& [k, v] : g.key) o << " " << v << " |";
    o << " " << g.runs.size() << " | " << nf << " | " << fixed(t.mean, 4) << " | " << fixed(t.std, 4) << " | "
      << fixed(t.median, 4) << " | " << fixed(t.min, 4) << " | " << fixed(t.max, 4) << " | "
      << fixed(Spread::of(rm).mean, 3) << " | "
      << (scored ? std::to_string(succ) + "/" + std::to_string(scored) : std::string("–")) << " | "
      << fixed(Spread::of(wall).mean, 1) << " | " << fixed(Spread::of(cpu).mean, 1) << " | "
      << fixed(Spread::of(rss).max, 0) << " | " << fixed(Spread::of(res).mean, 1) << " |";
    if (topo)
      o << " " << fixed(Spread::of(nodes).mean, 1) << " | " << fixed(Spread::of(edges).mean, 1) << " | "
        << fixed(Spread::of(acc).mean, 3) << " | " << fixed(Spread::of(door).mean, 3) << " | "
        << fixed(Spread::of(segr).mean, 3) << " | " << fixed(Spread::of(segp).mean, 3) << " | "
        << fixed(Spread::of(att).mean, 3) << " |";
    o << "\n";
  }
  bool any_failed = false;
  for (const auto& r : records) any_failed |= !r.ok();
  if (any_failed) {
    o << "\n## Failed runs\n\n| run | status | error |\n|---|---|---|\n";
    for (const auto& r : records)
      if (!r.ok()) o << "| " << r.index << " " << r.label << " | " << r.status << " | " << r.error << " |\n";
  }
  if (!records.empty())
    o << "\nCommit " << records.front().commit << ", host " << records.front().host << ", first run started "
      << records.front().start_time << ". Every run: `results.csv`, `results.jsonl`; its folder holds the "
      << "`options.ini` that reproduces it.\n";
  return o.str();
}

std::vector<RunRecord> collectRecords(const ExperimentPlan& plan) {
  std::vector<RunRecord> out;
  for (const auto& run : plan.runs) {
    RunRecord r;
    if (loadRecord(run, r)) out.push_back(std::move(r));
  }
  return out;
}

void writeResults(const ExperimentPlan& plan, const std::vector<RunRecord>& records) {
  const fs::path d(plan.output);
  OutputSet out;
  const std::string csv = resultsCsv(plan, records), jsonl = resultsJsonl(plan, records),
                    md = summaryMarkdown(plan, records);
  out.write((d / "results.csv").string(), [&](const std::string& p) { writeTextFileAtomically(p, csv); });
  out.write((d / "results.jsonl").string(), [&](const std::string& p) { writeTextFileAtomically(p, jsonl); });
  out.write((d / "summary.md").string(), [&](const std::string& p) { writeTextFileAtomically(p, md); });
  out.commit();
}

bool writeTablesAndPlots(const ExperimentPlan& plan, std::ostream& log) {
  const auto records = collectRecords(plan);
  writeResults(plan, records);
  const PlotFiles plots = drawPlots(plan, records);
  for (const auto& n : plots.notes) log << "gridtopo-experiment: note: " << n << "\n";
  std::size_t failed = 0;
  for (const auto& r : records) failed += !r.ok();
  log << "gridtopo-experiment: " << records.size() << " of " << plan.runs.size() << " runs recorded (" << failed
      << " failed); " << plan.output << "/summary.md, results.csv, results.jsonl, " << plots.pictures.size()
      << " plot pictures\n";
  return failed == 0;
}

}  // namespace gridtopo::experiment
