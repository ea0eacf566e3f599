#include "gridtopo/experiment/run_plan.h"

#include <mrpt/config/CConfigFileMemory.h>

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
  return false;
}

}  // namespace

std::string optionValue(const std::string& options_ini, const std::string& key) {
  const IniFile doc = IniFile::parse(options_ini, "<options>");
  for (const auto& s : doc.sections())
    if (const auto v = doc.value(s, key)) return *v;
  return "";
}

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
    const std::string ms = valueOf(run.params, "max_scans");
    if (!ms.empty()) run.max_scans = std::stol(ms);

    mrpt::config::CConfigFileMemory ini(base_text);
    for (const auto& e : spec.slam) ini.write(spec.base_section, e.key, e.value);
    for (const auto& [k, v] : run.params)
      if (!isRunKey(k)) ini.write(spec.base_section, k, v);
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
    run.options = o;
    run.options_ini = slam::slamOptionsIni(o, "slam");

    std::string label;
    for (const auto& k : plan.varied_keys) {
      const std::string v = valueOf(run.params, k);
      label += (label.empty() ? "" : "_") + (k == "dataset" || k == "proposal" ? sanitize(v) : sanitize(k + "-" + v));
    }
    const std::string key_text = run.options_ini + "max_scans = " + std::to_string(run.max_scans) +
                                 "\nlog = " + hashOf(run.log) + "\nrelations = " + hashOf(run.relations) + "\n";
    run.id = sha256Hex(key_text).substr(0, 16);
    if (!ids.insert(run.id).second)
      throw InputError(spec.path, 0, "[sweep]",
                       "run " + std::to_string(i) + " (" + label + ") repeats an earlier run's exact parameters");
    run.label = label;
    run.dir = (fs::path(plan.output) / "runs" / (label + "_" + run.id.substr(0, 8))).string();
    plan.runs.push_back(std::move(run));
  }
  return plan;
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
