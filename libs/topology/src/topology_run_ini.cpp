#include "gridtopo/topology/topology_run_ini.h"

#include <filesystem>
#include <vector>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/data_dir.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"

namespace fs = std::filesystem;

namespace gridtopo::topology {

std::string placesModelPath(const std::string& model) {
  if (model != kDefaultPlacesModel || fs::exists(model)) return model;
  const std::string shipped = findDataFile(kShippedPlacesModel, GRIDTOPO_BUILD_TIME_DATA_DIR);
  return shipped.empty() ? model : shipped;
}

const OptionSchema<TopologyRunSpec>& topologyRunSchema() {
  using S = TopologyRunSpec;
  static const OptionSchema<S> schema =
      OptionSchema<S>("gridtopo::topology::TopologyRunSpec")
          .add("map", &S::map, OptionRange::any(), "",
               "the occupancy map: .png/.pgm/.jpg (+ ROS .yaml), .yaml, .gridmap(.gz)")
          .add("model", &S::model, OptionRange::any(), "", "the place model from gridtopo-train")
          .add("output", &S::output, OptionRange::any(), "", "the output directory")
          .add("trajectory", &S::trajectory, OptionRange::any(), "",
               "the robot's trajectory in the map's frame (gridtopo-slam's trajectory.txt; empty = unknown): the map "
               "preparation keeps as places only cells it saw from near and can reach");
  return schema;
}

std::vector<std::string> topologyOptionKeys(const std::string& section) {
  for (const auto& s : describeTopologyOptions(TopologyOptions()))
    if (s.section == section) {
      std::vector<std::string> keys;
      for (const auto& k : s.keys) keys.push_back(k.key);
      return keys;
    }
  return {};
}

std::string topologyRunOptionsHelp() {
  return optionsHelp(kTopologyRunSection, topologyRunSchema().describe(TopologyRunSpec())) + "\n" +
         topologyOptionsHelp();
}

namespace {

std::string absolute(const std::string& p) { return fs::absolute(fs::path(p)).lexically_normal().string(); }

}  // namespace

TopologyRunSpec loadTopologyRunIni(const std::string& path) {
  if (!fs::is_regular_file(path)) throw InputError(path, "no such INI file");
  const IniFile ini = IniFile::read(path);
  const std::string run = kTopologyRunSection;
  ini.requireKnownSections({run, "topology", "relaxation", "correction"});
  ini.requireKnownKeys(run, topologyRunSchema().keys());
  for (const char* s : kTopologyOptionSections)
    ini.requireKnownKeys(s, topologyOptionKeys(s), "not an option of this section; see config-ini/topology.ini");
  TopologyRunSpec spec;
  spec.ini = path;
  topologyRunSchema().loadRun(spec, spec.lines, ini, run);
  try {
    spec.options = loadTopologyOptions(path);
  } catch (const InputError& e) {
    throw ini.withLine(e);  // loadTopologyOptions names "[section] key" without the line
  }
  return spec;
}

TopologyOptions loadTopologyOptionsIni(const std::string& path) {
  if (path.empty()) return TopologyOptions();
  if (!fs::is_regular_file(path)) throw InputError(path, "no such INI file");
  const IniFile ini = IniFile::read(path);
  ini.requireOptionsFile({"topology", "relaxation", "correction"}, "topology");
  for (const char* s : kTopologyOptionSections)
    ini.requireKnownKeys(s, topologyOptionKeys(s), "not an option of this section; see config-ini/topology.ini");
  try {
    return loadTopologyOptions(path);
  } catch (const InputError& e) {
    throw ini.withLine(e);
  }
}

void overrideRun(TopologyRunSpec& spec, const TopologyRunFlags& f) {
  spec.lines.overrideWith(f.model, spec.model, "model");
  spec.lines.overrideWith(f.output, spec.output, "output");
  spec.lines.overrideWith(f.trajectory, spec.trajectory, "trajectory");
  if (f.resolution) {
    if (!(*f.resolution > 0)) throw InputError("--resolution", "must be > 0");
    spec.options.resolution = *f.resolution;
  }
  if (f.threads) {
    if (*f.threads < 1) throw InputError("--threads", "must be >= 1");
    spec.options.threads = *f.threads;
  }
}

void checkTopologyRunSpec(const TopologyRunSpec& spec) {
  const std::string run = kTopologyRunSection;
  auto lineOf = [&](const std::string& key) { return spec.lines.of(key); };
  const std::string where = spec.ini.empty() ? "<command line>" : spec.ini;
  if (spec.map.empty())
    throw InputError(where, lineOf("map"), "[" + run + "] map",
                     "missing: name the map to label (or give it on the command line)");
  if (spec.output.empty())
    throw InputError(where, lineOf("output"), "[" + run + "] output", "missing: name the output directory (or give -o)");
  // A file named on the command line is left to its reader, which names it.
  auto requireFile = [&](const std::string& file, const std::string& key) {
    if (spec.fromIni(key) && !fs::exists(file))
      throw InputError(spec.ini, lineOf(key), "[" + run + "] " + key, "no such file '" + file + "'");
  };
  requireFile(spec.map, "map");
  requireFile(spec.model, "model");
  if (!spec.trajectory.empty()) requireFile(spec.trajectory, "trajectory");
}

TopologyRunSpec topologyRunOfCommandLine(const std::string& first, const std::optional<std::string>& options_ini,
                                         const TopologyRunFlags& flags) {
  const bool has_run_ini = first.size() > 4 && first.compare(first.size() - 4, 4, ".ini") == 0;
  if (has_run_ini && options_ini) throw UsageError("give the options either in RUN.ini or with -c, not both");
  if (!has_run_ini && !flags.output) throw UsageError("name the output directory (-o), or give a RUN.ini");
  TopologyRunSpec spec = has_run_ini ? loadTopologyRunIni(first) : TopologyRunSpec{};
  if (!has_run_ini) {
    spec.map = first;
    spec.options = loadTopologyOptionsIni(options_ini.value_or(""));
  }
  overrideRun(spec, flags);
  spec.model = placesModelPath(spec.model);
  checkTopologyRunSpec(spec);
  return spec;
}

std::string topologyRunIni(const TopologyRunSpec& spec) {
  TopologyRunSpec run = spec;
  run.map = absolute(spec.map);
  run.model = absolute(spec.model);
  run.output = absolute(spec.output);
  if (!spec.trajectory.empty()) run.trajectory = absolute(spec.trajectory);
  return topologyRunSchema().ini(run, kTopologyRunSection) + "\n" + topologyOptionsIni(spec.options);
}

}  // namespace gridtopo::topology
