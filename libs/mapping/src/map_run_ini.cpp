#include "gridtopo/mapping/map_run_ini.h"

#include <mrpt/config/CConfigFile.h>

#include <filesystem>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"
#include "gridtopo/core/run_args.h"
#include "gridtopo/slam/options_ini.h"
#include "gridtopo/slam/slam_run_ini.h"
#include "gridtopo/topology/topology_run_ini.h"

namespace fs = std::filesystem;

namespace gridtopo::mapping {

namespace {
std::string absolute(const std::string& p) { return fs::absolute(fs::path(p)).lexically_normal().string(); }
}  // namespace

MapRunSpec::MapRunSpec() : model(topology::kDefaultPlacesModel) {}

const OptionSchema<MapRunSpec>& mapRunSchema() {
  using S = MapRunSpec;
  static const OptionSchema<S> schema =
      OptionSchema<S>("gridtopo::mapping::MapRunSpec")
          .add("input", &S::input, OptionRange::any(), "", "the log: CARMEN (.clf, .log, optionally .gz) or MRPT rawlog")
          .add("output", &S::output, OptionRange::any(), "", "the output directory: OUT/slam, OUT/topology, OUT/options.ini")
          .add("model", &S::model, OptionRange::any(), "", "the place model from gridtopo-train")
          .add("max_scans", &S::max_scans, OptionRange::any(), "scans", "feed only the first max_scans scans; 0 = all");
  return schema;
}

std::string mapRunOptionsHelp() {
  return optionsHelp(kMapRunSection, mapRunSchema().describe(MapRunSpec())) + "\n" +
         optionsHelp("slam", slam::slamOptionSchema().describe(slam::SlamOptions())) + "\n" +
         topology::topologyOptionsHelp() + "\n" +
         optionsHelp(kTopologyBuilderSection, topologyBuilderOptionSchema().describe(TopologyBuilderOptions()));
}

MapRunSpec loadMapRunIni(const std::string& path) {
  if (!fs::is_regular_file(path)) throw InputError(path, "no such INI file");
  const IniFile ini = IniFile::read(path);
  const std::string run = kMapRunSection;
  std::vector<std::string> sections = {run, "slam", slam::LoopClosureOptions::kSection, kTopologyBuilderSection};
  for (const char* s : topology::kTopologyOptionSections) sections.push_back(s);
  ini.requireKnownSections(sections);
  ini.requireKnownKeys(run, mapRunSchema().keys());
  ini.requireKnownKeys("slam", slam::slamOptionKeys(), "not an option of the filter; see config-ini/slam.ini");
  ini.requireKnownKeys(slam::LoopClosureOptions::kSection, slam::loopClosureOptionSchema().keys(),
                       "not an option of the loop closure; see config-ini/slam.ini");
  for (const char* s : topology::kTopologyOptionSections)
    ini.requireKnownKeys(s, topology::topologyOptionKeys(s), "not an option of this section; see config-ini/topology.ini");
  ini.requireKnownKeys(kTopologyBuilderSection, topologyBuilderOptionKeys());

  MapRunSpec spec;
  spec.ini = path;
  mapRunSchema().loadRun(spec, spec.lines, ini, run);
  try {
    if (ini.hasSection("slam")) spec.slam = slam::loadSlamOptionsIni(path, "slam");
    spec.topology = topology::loadTopologyOptions(path);
    spec.builder.loadFromConfigFile(mrpt::config::CConfigFile(path), kTopologyBuilderSection);
  } catch (const InputError& e) {
    throw ini.withLine(e);  // the options' loaders name "[section] key" without the line
  }
  return spec;
}

void overrideRun(MapRunSpec& spec, const MapRunFlags& f) {
  spec.lines.overrideWith(f.input, spec.input, "input");
  spec.lines.overrideWith(f.output, spec.output, "output");
  spec.lines.overrideWith(f.model, spec.model, "model");
  if (f.max_scans) {
    if (*f.max_scans < 0) throw InputError("<command line>", 0, "--max-scans", "must be >= 0");
    spec.max_scans = static_cast<std::size_t>(*f.max_scans);
  }
}

MapRunSpec mapRunOfCommandLine(const std::string& run_ini, const MapRunFlags& run, const slam::SlamOptionFlags& slam) {
  requireRunIniOrInputOutput(run_ini, run.input.has_value(), run.output.has_value());
  MapRunSpec spec = run_ini.empty() ? MapRunSpec{} : loadMapRunIni(run_ini);
  overrideRun(spec, run);
  spec.model = topology::placesModelPath(spec.model);
  slam::overrideOptions(spec.slam, slam);
  return spec;
}

void checkMapRunSpec(const MapRunSpec& spec) {
  const std::string run = kMapRunSection;
  const std::string where = spec.ini.empty() ? "<command line>" : spec.ini;
  auto lineOf = [&](const std::string& key) { return spec.lines.of(key); };
  if (spec.input.empty())
    throw InputError(where, lineOf("input"), "[" + run + "] input", "missing: name the log to read (or give -i)");
  if (spec.output.empty())
    throw InputError(where, lineOf("output"), "[" + run + "] output", "missing: name the output directory (or give -o)");
  auto requireFile = [&](const std::string& file, const std::string& key) {
    if (fs::exists(file)) return;
    if (spec.fromIni(key)) throw InputError(spec.ini, lineOf(key), "[" + run + "] " + key, "no such file '" + file + "'");
    throw InputError(file, "no such file");
  };
  requireFile(spec.input, "input");
  requireFile(spec.model, "model");
}

std::string mapRunIni(const MapRunSpec& spec) {
  MapRunSpec run = spec;
  run.input = absolute(spec.input);
  run.output = absolute(spec.output);
  run.model = absolute(spec.model);
  return mapRunSchema().ini(run, kMapRunSection) + "\n" + slam::slamOptionsIni(spec.slam, "slam") + "\n" +
         topology::topologyOptionsIni(spec.topology) + "\n" + topologyBuilderOptionsIni(spec.builder);
}

}  // namespace gridtopo::mapping
