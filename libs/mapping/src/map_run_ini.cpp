#include "gridtopo/mapping/map_run_ini.h"

#include <mrpt/config/CConfigFile.h>

#include <filesystem>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"
#include "gridtopo/core/ini_value.h"
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
  std::vector<std::string> sections = {run, "slam", kTopologyBuilderSection};
  for (const char* s : topology::kTopologyOptionSections) sections.push_back(s);
  ini.requireKnownSections(sections);
  ini.requireKnownKeys(run, mapRunSchema().keys());
  ini.requireKnownKeys("slam", slam::slamOptionKeys(), "not an option of the filter; see config-ini/slam.ini");
  for (const char* s : topology::kTopologyOptionSections)
    ini.requireKnownKeys(s, topology::topologyOptionKeys(s), "not an option of this section; see config-ini/topology.ini");
  ini.requireKnownKeys(kTopologyBuilderSection, topologyBuilderOptionKeys());

  MapRunSpec spec;
  spec.ini = path;
  auto text = [&](const char* key, std::string& target, bool& from_ini) {
    if (const auto v = ini.value(run, key); v && !v->empty()) {
      target = *v;
      from_ini = true;
    }
  };
  text("input", spec.input, spec.input_from_ini);
  text("output", spec.output, spec.output_from_ini);
  text("model", spec.model, spec.model_from_ini);
  unsigned long max_scans = 0;
  if (ini.parseValue(run, "max_scans", max_scans)) spec.max_scans = max_scans;
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
  if (f.input) {
    spec.input = *f.input;
    spec.input_from_ini = false;
  }
  if (f.output) {
    spec.output = *f.output;
    spec.output_from_ini = false;
  }
  if (f.model) {
    spec.model = *f.model;
    spec.model_from_ini = false;
  }
  if (f.max_scans) {
    if (*f.max_scans < 0) throw InputError("<command line>", 0, "--max-scans", "must be >= 0");
    spec.max_scans = static_cast<std::size_t>(*f.max_scans);
  }
}

void checkMapRunSpec(const MapRunSpec& spec) {
  const std::string run = kMapRunSection;
  const std::string where = spec.ini.empty() ? "<command line>" : spec.ini;
  auto lineOf = [&](const std::string& key) {
    return spec.ini.empty() ? std::size_t{0} : IniFile::read(spec.ini).lineOrSection(run, key);
  };
  if (spec.input.empty())
    throw InputError(where, lineOf("input"), "[" + run + "] input", "missing: name the log to read (or give -i)");
  if (spec.output.empty())
    throw InputError(where, lineOf("output"), "[" + run + "] output", "missing: name the output directory (or give -o)");
  auto requireFile = [&](const std::string& file, bool from_ini, const std::string& key) {
    if (fs::exists(file)) return;
    if (from_ini) throw InputError(spec.ini, lineOf(key), "[" + run + "] " + key, "no such file '" + file + "'");
    throw InputError(file, "no such file");
  };
  requireFile(spec.input, spec.input_from_ini, "input");
  requireFile(spec.model, spec.model_from_ini, "model");
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
