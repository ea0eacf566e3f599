#include "gridtopo/experiment/run_plan.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"
#include "gridtopo/experiment/content_hash.h"
#include "gridtopo/experiment/subprocess.h"
#include "gridtopo/slam/options_ini.h"
#include "gridtopo/slam/slam_options.h"
#include "gridtopo/slam/slam_run_ini.h"
#include "gridtopo/topology/topology_run_ini.h"

namespace fs = std::filesystem;

namespace gridtopo::experiment {
namespace {

std::string readText(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, "cannot read the file");
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string sanitize(const std::string& s) {
  std::string out;
  for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-') ? c : '-';
  return out;
}

bool isRunKey(const std::string& k) {
  for (const char* r : kRunKeys)
    if (k == r) return true;
  return isTopologyKey(k);
}

/// "[section] key" of a topology option's error (its loaders name "[section]" as the file and the key as the field).
std::pair<std::string, std::string> topologyErrorKey(const InputError& e) {
  const auto close = e.field().find("] ");
  if (e.field().rfind("[", 0) == 0 && close != std::string::npos)
    return {e.field().substr(1, close - 1), e.field().substr(close + 2)};
  if (e.file().size() > 2 && e.file().front() == '[' && e.file().back() == ']')
    return {e.file().substr(1, e.file().size() - 2), e.field()};
  return {"topology", e.field()};
}

}  // namespace

std::string optionValue(const std::string& options_ini, const std::string& key) {
  const IniFile doc = IniFile::parse(options_ini, "<options>");
  for (const auto& s : doc.sections())
    if (const auto v = doc.value(s, key)) return *v;
  return "";
}

constexpr const char* kLoopClosurePrefix = "loop_closure.";

ExperimentPlan planExperiment(const ExperimentSpec& spec, const std::string& output) {
  ExperimentPlan plan;
  plan.spec = spec;
  plan.output = output.empty() ? spec.output : output;
  if (plan.output.empty())
    throw InputError(spec.path, 0, "[experiment] output", "no results folder: set output = ... or give -o");
  plan.output = fs::absolute(plan.output).lexically_normal().string();

  const IniFile defaults = IniFile::parse(slam::slamOptionsIni(slam::SlamOptions(), "slam"), "<defaults>");
  std::set<std::string> known;
  for (const auto& key : defaults.keys("slam")) {
    plan.slam_keys.push_back(key);
    known.insert(key);
  }
  // The loop closure's keys, as "loop_closure.KEY" (its own section in the runs' options.ini).
  for (const auto& key : slam::loopClosureOptionSchema().keys()) known.insert(kLoopClosurePrefix + key);

  // Where each option key is set in the experiment INI, to name it when its value is refused.
  std::map<std::string, std::pair<std::string, std::size_t>> origin;  // key -> ("[slam]" | "[sweep]", line)
  for (const auto& e : spec.slam) {
    if (!known.count(e.key))
      throw InputError(spec.path, e.line, "[slam] " + e.key,
                       "unknown key (not an option of gridtopo-slam; see config-ini/slam.ini)");
    origin[e.key] = {"[slam]", e.line};
  }
  for (const auto& k : spec.sweep) {
    if (!known.count(k.key) && !isRunKey(k.key))
      throw InputError(spec.path, k.line, "[sweep] " + k.key,
                       "unknown key (expected an option of gridtopo-slam, see config-ini/slam.ini, or dataset, "
                       "max_scans)");
    origin[k.key] = {"[sweep]", k.line};
  }

  std::string base_text;
  if (!spec.base_ini.empty()) {
    base_text = readText(spec.base_ini);
    const IniFile base = IniFile::parse(base_text, spec.base_ini);
    base.requireNoRepeats();
    if (!base.hasSection(spec.base_section))
      throw InputError(spec.base_ini, 0, "[" + spec.base_section + "]", "section not found");
    for (const auto& key : base.keys(spec.base_section))
      if (!known.count(key))
        throw InputError(spec.base_ini, base.line(spec.base_section, key), "[" + spec.base_section + "] " + key,
                         "unknown key (not an option of gridtopo-slam; see config-ini/slam.ini)");
  }

  // Topology options: every section.key the topology INI knows; where each is set (to name it when refused).
  std::string topology_text;
  std::map<std::string, std::pair<std::string, std::size_t>> topology_origin;  // section.key -> (where, line)
  if (spec.topologyRuns()) {
    const IniFile defaults_t = IniFile::parse(topology::topologyOptionsIni(topology::TopologyOptions()), "<defaults>");
    std::set<std::string> known_t;
    for (const char* sec : kTopologySections)
      for (const auto& key : defaults_t.keys(sec)) {
        plan.topology_keys.push_back(std::string(sec) + "." + key);
        known_t.insert(std::string(sec) + "." + key);
      }
    if (!spec.topology_ini.empty()) {
      topology_text = readText(spec.topology_ini);
      const IniFile t = IniFile::parse(topology_text, spec.topology_ini);
      t.requireNoRepeats();
      for (const auto& sec : t.sections())
        for (const auto& key : t.keys(sec))
          if (!known_t.count(sec + "." + key))
            throw InputError(spec.topology_ini, t.line(sec, key), "[" + sec + "] " + key,
                             "unknown key (not a topology option; see config-ini/topology.ini)");
    }
    for (const auto& e : spec.topology) {
      if (!known_t.count(e.section + "." + e.key))
        throw InputError(spec.path, e.line, "[" + e.section + "] " + e.key,
                         "unknown key (not a topology option; see config-ini/topology.ini)");
      topology_origin[e.section + "." + e.key] = {"[" + e.section + "] " + e.key, e.line};
    }
    for (const auto& k : spec.sweep)
      if (isTopologyKey(k.key)) {
        if (!known_t.count(k.key))
          throw InputError(spec.path, k.line, "[sweep] " + k.key,
                           "unknown key (not a topology option; see config-ini/topology.ini)");
        topology_origin[k.key] = {"[sweep] " + k.key, k.line};
      }
  }

  std::vector<SweepKey> keys = spec.sweep;
  bool has_dataset = false;
  for (const auto& k : keys) has_dataset |= k.key == "dataset";
  if (!has_dataset) {
    SweepKey d{"dataset", {}, 0};
    for (const auto& ds : spec.datasets) d.values.push_back(ds.name);
    keys.insert(keys.begin(), d);
  }
  for (const auto& k : keys)
    if (k.values.size() > 1 || k.key == "dataset") {
      if (k.key == "dataset") plan.varied_keys.insert(plan.varied_keys.begin(), k.key);
      else plan.varied_keys.push_back(k.key);
    }

  std::map<std::string, std::string> file_hash;
  auto hashOf = [&](const std::string& p) {
    if (p.empty()) return std::string("none");
    auto it = file_hash.find(p);
    if (it == file_hash.end()) it = file_hash.emplace(p, sha256OfFile(p)).first;
    return it->second;
  };

  const auto assignments = expandSweep(keys, spec.zip_groups);
  std::set<std::string> ids;
  for (std::size_t i = 0; i < assignments.size(); ++i) {
    PlannedRun run;
    run.index = i;
    run.params = assignments[i];
    run.dataset = valueOf(run.params, "dataset");
    const DatasetSpec* ds = spec.dataset(run.dataset);
    run.log = ds->log;
    run.relations = ds->relations;
    run.slam = !ds->log.empty();
    const std::string ms = valueOf(run.params, "max_scans");
    if (!ms.empty()) run.max_scans = std::stol(ms);

    mrpt::config::CConfigFileMemory ini(base_text);
    auto writeKey = [&](const std::string& k, const std::string& v) {
      if (k.rfind(kLoopClosurePrefix, 0) == 0)
        ini.write(slam::LoopClosureOptions::kSection, k.substr(std::string(kLoopClosurePrefix).size()), v);
      else
        ini.write(spec.base_section, k, v);
    };
    for (const auto& e : spec.slam) writeKey(e.key, e.value);
    for (const auto& [k, v] : run.params)
      if (!isRunKey(k)) writeKey(k, v);
    slam::SlamOptions o;
    try {
      o.loadFromConfigFile(ini, spec.base_section);
    } catch (const InputError& e) {
      const auto close = e.field().find("] ");
      const std::string key = close == std::string::npos ? e.field() : e.field().substr(close + 2);
      const auto it = origin.find(key);
      if (it == origin.end()) throw InputError(spec.base_ini, 0, e.field(), e.message());
      throw InputError(spec.path, it->second.second, it->second.first + " " + key,
                       e.message() + (it->second.first == "[sweep]" ? " (run " + std::to_string(i) + ")" : ""));
    }
    run.threads = o.threads;
    if (run.slam) {
      run.options = o;
      run.options_ini = slam::slamOptionsIni(o, "slam");
    } else {
      run.threads = 0;
    }

    std::string label;
    for (const auto& k : plan.varied_keys) {
      const std::string v = valueOf(run.params, k);
      label += (label.empty() ? "" : "_") + (k == "dataset" || k == "proposal" ? sanitize(v) : sanitize(k + "-" + v));
    }
    if (spec.topologyRuns()) {
      run.topology = true;
      mrpt::config::CConfigFileMemory tini(topology_text);
      for (const auto& e : spec.topology) tini.write(e.section, e.key, e.value);
      for (const auto& [k, v] : run.params)
        if (isTopologyKey(k)) tini.write(k.substr(0, k.find('.')), k.substr(k.find('.') + 1), v);
      try {
        run.topology_options.loadFromConfigFile(tini, "topology");
      } catch (const InputError& e) {
        const auto [sec, key] = topologyErrorKey(e);
        const auto it = topology_origin.find(sec + "." + key);
        if (it == topology_origin.end())
          throw InputError(spec.topology_ini.empty() ? spec.path : spec.topology_ini, 0, "[" + sec + "] " + key,
                           e.message());
        throw InputError(spec.path, it->second.second, it->second.first,
                         e.message() + (it->second.first.rfind("[sweep]", 0) == 0 ? " (run " + std::to_string(i) + ")"
                                                                                  : ""));
      }
      run.topology_options_ini = topology::topologyOptionsIni(run.topology_options);
      run.model = spec.places_model;
      run.plan = ds->plan;
      run.plan_labels = ds->plan_labels;
      run.plan_segmentation = ds->plan_segmentation;
      if (!run.slam) run.map = ds->map;
      run.threads = std::max(run.threads, run.topology_options.threads);
    }
    // The id: the SLAM part exactly as for SLAM-only experiments (their ids do not change), then the topology's.
    std::string key_text;
    if (run.slam)
      key_text = run.options_ini + "max_scans = " + std::to_string(run.max_scans) + "\nlog = " + hashOf(run.log) +
                 "\nrelations = " + hashOf(run.relations) + "\n";
    if (run.topology)
      key_text += "[topology of the run]\n" + run.topology_options_ini + "map = " + hashOf(run.map) +
                  "\nmodel = " + hashOf(run.model) + "\nplan = " + hashOf(run.plan) + "\nplan_labels = " +
                  hashOf(run.plan_labels) + "\nplan_segmentation = " + hashOf(run.plan_segmentation) + "\n";
    run.id = sha256Hex(key_text).substr(0, 16);
    if (!ids.insert(run.id).second)
      throw InputError(spec.path, 0, "[sweep]",
                       "run " + std::to_string(i) + " (" + label + ") repeats an earlier run's exact parameters");
    run.label = label;
    run.dir = (fs::path(plan.output) / "runs" / (label + "_" + run.id.substr(0, 8))).string();
    if (run.topology && run.slam) run.map = (fs::path(run.dir) / "out" / "map.yaml").string();
    plan.runs.push_back(std::move(run));
  }
  return plan;
}

std::string topologyIniText(const ExperimentPlan& plan, const PlannedRun& run) {
  topology::TopologyRunSpec spec;
  spec.map = run.map;
  spec.model = run.model;
  spec.output = (fs::path(run.dir) / "topology").string();
  // A run's own SLAM map comes with the robot's trajectory: its door passages (as gridtopo-map's topology).
  if (run.slam) spec.trajectory = (fs::path(run.dir) / "out" / "trajectory.txt").string();
  spec.options = run.topology_options;
  return "# Topology of run " + std::to_string(run.index) + " (" + run.label + ") of experiment '" + plan.spec.name +
         "', id " + run.id + ": gridtopo-topology " + (fs::path(run.dir) / "topology.ini").string() + "\n" +
         topology::topologyRunIni(spec);
}

std::vector<RunStage> runStages(const PlannedRun& run, const Executables& exe) {
  const fs::path dir(run.dir);
  std::vector<RunStage> stages;
  if (run.slam) stages.push_back({"slam", slamCommand(run, exe.slam), (dir / "slam.log").string()});
  if (run.topology) {
    stages.push_back({"topology", {exe.topology, (dir / "topology.ini").string(), "-q"}, (dir / "topology.log").string()});
    if (!run.plan.empty())
      stages.push_back({"compare",
                        {exe.compare, run.map, (dir / "topology").string(), "-c",
                         (dir / "topology" / "options.ini").string(), "--reference-map", run.plan, "--reference-labels",
                         run.plan_labels, "--reference-segmentation", run.plan_segmentation, "-j",
                         (dir / "topology" / "compare.json").string()},
                        (dir / "compare.log").string()});
    if (!run.plan.empty() && run.slam) {  // the graph along the run's trajectory too
      auto& compare = stages.back().argv;
      compare.push_back("-t");
      compare.push_back((dir / "out" / "trajectory.txt").string());
    }
  }
  return stages;
}

std::vector<std::string> slamCommand(const PlannedRun& run, const std::string& slam_exe) {
  return {slam_exe, (fs::path(run.dir) / "options.ini").string(), "-q"};
}

std::string runIniText(const ExperimentPlan& plan, const PlannedRun& run, const std::string& slam_exe) {
  std::ostringstream o;
  o << "# Run " << run.index << " (" << run.label << ") of experiment '" << plan.spec.name << "' ("
    << plan.spec.path << "), id " << run.id << ".\n";
  o << "# Dataset " << run.dataset << ": log " << run.log;
  if (!run.relations.empty()) o << ", relations " << run.relations;
  o << (run.max_scans > 0 ? ", first " + std::to_string(run.max_scans) + " scans" : std::string()) << ".\n";
  o << "# Reproduce with:\n#  ";
  for (const auto& a : slamCommand(run, slam_exe)) o << ' ' << shellQuote(a);
  o << "\n";
  slam::SlamRunSpec spec;
  spec.input = run.log;
  spec.output = (fs::path(run.dir) / "out").string();
  spec.max_scans = run.max_scans > 0 ? static_cast<std::size_t>(run.max_scans) : 0;
  spec.options = run.options;
  o << slam::slamRunIni(spec);
  return o.str();
}

}  // namespace gridtopo::experiment
