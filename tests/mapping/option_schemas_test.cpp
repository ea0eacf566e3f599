// The key tables of every options struct against the documented INI files and against themselves:
//  - each config-ini/*.ini documents exactly the keys of the tables (so the docs cannot drift), with the defaults;
//  - save -> load gives back every key of every struct with a non-default value, exactly;
//  - every key's value out of its range is refused with the section and the key.
#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/run_app.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"
#include "gridtopo/core/option_schema.h"
#include "gridtopo/eval/relations_metric.h"
#include "gridtopo/eval/relations_run.h"
#include "gridtopo/mapping/map_run_ini.h"
#include "gridtopo/mapping/topology_builder_options.h"
#include "gridtopo/places/features.h"
#include "gridtopo/places/scan_simulation.h"
#include "gridtopo/places/training.h"
#include "gridtopo/slam/options_ini.h"
#include "gridtopo/slam/slam_run_ini.h"
#include "gridtopo/topology/topology_run_ini.h"

using namespace gridtopo;

namespace {

const std::string kIni = std::string(GRIDTOPO_SOURCE_DIR) + "/config-ini/";

std::set<std::string> keySet(const std::vector<std::string>& keys) { return {keys.begin(), keys.end()}; }
std::set<std::string> keySet(const std::vector<OptionDescription>& keys) {
  std::set<std::string> s;
  for (const auto& k : keys) s.insert(k.key);
  return s;
}

/// An options struct seen through its tables: describe the current values, load a config into a fresh struct.
struct Subject {
  std::string name;
  std::function<std::vector<OptionSection>()> defaults;
  /// Loads `cfg` into a default struct and describes it; throws what the struct's loading throws.
  std::function<std::vector<OptionSection>(const mrpt::config::CConfigFileMemory&)> load;
  /// Values tried first for keys that otherValues cannot serve (free text, rules between keys).
  std::map<std::string, std::vector<std::string>> other_text = {};
};

/// A subject of one struct with one table in one section.
template <class S>
Subject oneTable(const std::string& name, const std::string& section, const OptionSchema<S>& (*schema)(),
                 std::map<std::string, std::vector<std::string>> other_text = {}) {
  return {name, [=] { return std::vector<OptionSection>{{section, schema().describe(S{})}}; },
          [=](const mrpt::config::CConfigFileMemory& cfg) {
            S o;
            schema().load(o, cfg, section);
            return std::vector<OptionSection>{{section, schema().describe(o)}};
          },
          std::move(other_text)};
}

std::vector<Subject> subjects() {
  return {
      {"SlamOptions", [] { return std::vector<OptionSection>{{"slam", slam::slamOptionSchema().describe({})}}; },
       [](const mrpt::config::CConfigFileMemory& cfg) {
         slam::SlamOptions o;
         o.loadFromConfigFile(cfg, "slam");
         return std::vector<OptionSection>{{"slam", slam::slamOptionSchema().describe(o)}};
       }},
      {"TopologyOptions", [] { return topology::describeTopologyOptions({}); },
       [](const mrpt::config::CConfigFileMemory& cfg) {
         topology::TopologyOptions o;
         o.loadFromConfigFile(cfg, "topology");
         return topology::describeTopologyOptions(o);
       }},
      {"TopologyBuilderOptions",
       [] {
         return std::vector<OptionSection>{
             {mapping::kTopologyBuilderSection, mapping::topologyBuilderOptionSchema().describe({})}};
       },
       [](const mrpt::config::CConfigFileMemory& cfg) {
         mapping::TopologyBuilderOptions o;
         o.loadFromConfigFile(cfg, mapping::kTopologyBuilderSection);
         return std::vector<OptionSection>{
             {mapping::kTopologyBuilderSection, mapping::topologyBuilderOptionSchema().describe(o)}};
       }},
      oneTable("ScanSimulationOptions", "scan_simulation", places::scanSimulationOptionSchema,
               {{"num_beams", {"364"}}}),  // a multiple of 4
      // simulated_maps must name a directory that exists; capped_ranges is a list of ranges.
      oneTable("TrainingOptions", "training", places::trainingOptionSchema,
               {{"simulated_maps", {std::string(GRIDTOPO_SOURCE_DIR) + "/datasets/places/derived"}},
                {"order", {"corridor,room,doorway"}}}),
      oneTable("FeatureOptions", "features", places::featureOptionSchema,
               {{"capped_ranges", {"7.5, 12.25, 0.1000000000000000055511151231257827"}}}),
      oneTable("RelationsMetricOptions", "relations_metric", eval::relationsMetricOptionSchema),
  };
}

/// Values other than the default that a key may take (the first that loads is used).
std::vector<std::string> otherValues(const OptionDescription& k) {
  switch (k.type) {
    case OptionType::Bool: return {k.default_value == "true" ? "false" : "true"};
    case OptionType::Word: {
      std::vector<std::string> w;
      for (const auto& word : k.words)
        if (word != k.default_value) w.push_back(word);
      return w;
    }
    case OptionType::Int: {
      const long d = std::stol(k.default_value);
      return {std::to_string(d + 1), std::to_string(d - 1), std::to_string(d + 2)};
    }
    case OptionType::Real: {
      const double d = std::stod(k.default_value);
      // Not short decimals, so that a save with too few digits would not load back the same value.
      return {iniText(d * 0.7 + 0.0123456789), iniText(d * 1.3 + 0.0123456789), iniText(d - 0.0123456789),
              iniText(d * 0.5), iniText(d + 1.0 / 3)};
    }
    case OptionType::Text: return {k.default_value + "_other"};
  }
  return {};
}

/// Values outside `range` ("[a, b]", "(a, b]", "[a, b)", ">= a", "> a", "< a"; ints stay whole).
std::vector<std::string> outOfRange(const OptionDescription& k) {
  std::vector<std::string> v;
  const std::string& r = k.range;
  if (r.empty() || k.type == OptionType::Word) return v;
  auto number = [&](double x) { return k.type == OptionType::Int ? std::to_string(static_cast<long>(x)) : iniText(x); };
  const double step = k.type == OptionType::Int ? 1 : 1e-6;
  if (r[0] == '[' || r[0] == '(') {
    const double lo = std::stod(r.substr(1)), hi = std::stod(r.substr(r.find(',') + 1));
    v.push_back(number(r[0] == '(' ? lo : lo - step));
    v.push_back(number(r.back() == ')' ? hi : hi + step));
  } else if (r.rfind(">= ", 0) == 0) {
    v.push_back(number(std::stod(r.substr(3)) - step));
  } else if (r.rfind("> ", 0) == 0) {
    v.push_back(number(std::stod(r.substr(2))));
  } else if (r.rfind("< ", 0) == 0) {
    v.push_back(number(std::stod(r.substr(2))));
  }
  return v;
}

bool loads(const Subject& s, const mrpt::config::CConfigFileMemory& cfg) {
  try {
    s.load(cfg);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace

TEST(OptionSchemas, DocumentedIniFilesHoldExactlyTheTablesKeys) {
  // The option files: every key, with its default.
  const IniFile slam_ini = IniFile::read(kIni + "slam.ini");
  EXPECT_EQ(slam_ini.sections(), (std::vector<std::string>{"slam", slam::LoopClosureOptions::kSection}));
  EXPECT_EQ(keySet(slam_ini.keys("slam")), keySet(slam::slamOptionSchema().keys()));
  EXPECT_EQ(keySet(slam_ini.keys(slam::LoopClosureOptions::kSection)), keySet(slam::loopClosureOptionSchema().keys()));
  const IniFile topo_ini = IniFile::read(kIni + "topology.ini");
  EXPECT_EQ(topo_ini.sections(), (std::vector<std::string>{"topology", "relaxation", "correction"}));
  for (const auto& s : topology::describeTopologyOptions({}))
    EXPECT_EQ(keySet(topo_ini.keys(s.section)), keySet(s.keys)) << "[" << s.section << "] of topology.ini";
  // Their values are the code's defaults.
  EXPECT_EQ(slam::slamOptionsIni(slam::loadSlamOptionsIni(kIni + "slam.ini")), slam::slamOptionsIni({}));
  EXPECT_EQ(topology::topologyOptionsIni(topology::loadTopologyOptions(kIni + "topology.ini")),
            topology::topologyOptionsIni({}));

  // The example RUN.ini files: their run sections document every key of the run tables.
  EXPECT_EQ(keySet(IniFile::read(kIni + "run-slam.ini").keys("slam_run")), keySet(slam::slamRunSchema().keys()));
  EXPECT_EQ(keySet(IniFile::read(kIni + "run-topology.ini").keys("topology_run")),
            keySet(topology::topologyRunSchema().keys()));
  const IniFile map_ini = IniFile::read(kIni + "run-map.ini");
  EXPECT_EQ(keySet(map_ini.keys("map_run")), keySet(mapping::mapRunSchema().keys()));
  EXPECT_EQ(keySet(map_ini.keys(mapping::kTopologyBuilderSection)),
            keySet(mapping::topologyBuilderOptionSchema().keys()));
  // The training INI and the relations metric's: every key of their tables, with its default.
  const IniFile train_ini = IniFile::read(kIni + "topology_train.ini");
  EXPECT_EQ(train_ini.sections(), (std::vector<std::string>{"scan_simulation", "features", "training"}));
  EXPECT_EQ(keySet(train_ini.keys("scan_simulation")), keySet(places::scanSimulationOptionSchema().keys()));
  EXPECT_EQ(keySet(train_ini.keys("features")), keySet(places::featureOptionSchema().keys()));
  EXPECT_EQ(keySet(train_ini.keys("training")), keySet(places::trainingOptionSchema().keys()));
  const auto train = places::loadTrainingConfig(kIni + "topology_train.ini");
  EXPECT_EQ(places::scanSimulationOptionSchema().ini(train.scan, "s"), places::scanSimulationOptionSchema().ini({}, "s"));
  EXPECT_EQ(places::featureOptionSchema().ini(train.features, "f"), places::featureOptionSchema().ini({}, "f"));
  EXPECT_EQ(places::trainingOptionSchema().ini(train.training, "t"), places::trainingOptionSchema().ini({}, "t"));
  const IniFile eval_ini = IniFile::read(kIni + "eval.ini");
  EXPECT_EQ(eval_ini.sections(), std::vector<std::string>{"relations_metric"});
  EXPECT_EQ(keySet(eval_ini.keys("relations_metric")), keySet(eval::relationsMetricOptionSchema().keys()));
  EXPECT_EQ(eval::relationsMetricOptionSchema().ini(eval::loadRelationsMetricIni(kIni + "eval.ini"), "r"),
            eval::relationsMetricOptionSchema().ini({}, "r"));

  // ... and they load.
  EXPECT_NO_THROW(slam::loadSlamRunIni(kIni + "run-slam.ini"));
  EXPECT_NO_THROW(topology::loadTopologyRunIni(kIni + "run-topology.ini"));
  EXPECT_NO_THROW(mapping::loadMapRunIni(kIni + "run-map.ini"));
}

TEST(OptionSchemas, SaveThenLoadGivesBackEveryNonDefaultValueExactly) {
  for (const Subject& s : subjects()) {
    // Every key at a value other than its default that the struct accepts (rules between keys included).
    mrpt::config::CConfigFileMemory cfg;
    std::size_t keys = 0;
    for (const auto& section : s.defaults())
      for (const auto& k : section.keys) {
        ++keys;
        bool set = false;
        std::vector<std::string> candidates = otherValues(k);
        if (const auto it = s.other_text.find(k.key); it != s.other_text.end())
          candidates.insert(candidates.begin(), it->second.begin(), it->second.end());
        for (const auto& v : candidates) {
          mrpt::config::CConfigFileMemory trial;
          trial.setContent(cfg.getContent());
          trial.write(section.section, k.key, v);
          if (!loads(s, trial)) continue;
          cfg.write(section.section, k.key, v);
          set = true;
          break;
        }
        EXPECT_TRUE(set) << s.name << ": no other value of [" << section.section << "] " << k.key << " loads";
      }
    ASSERT_GT(keys, 0u);
    const auto changed = s.load(cfg);
    const auto defaults = s.defaults();
    // Saved as the struct saves itself, loaded back: the same values, none at its default.
    mrpt::config::CConfigFileMemory saved;
    for (const auto& section : changed)
      for (const auto& k : section.keys) saved.write(section.section, k.key, k.value);
    const auto back = s.load(saved);
    ASSERT_EQ(back.size(), changed.size());
    for (std::size_t i = 0; i < back.size(); ++i)
      for (std::size_t j = 0; j < back[i].keys.size(); ++j) {
        const auto& k = back[i].keys[j];
        EXPECT_EQ(k.value, changed[i].keys[j].value) << s.name << " [" << back[i].section << "] " << k.key;
        EXPECT_NE(k.value, defaults[i].keys[j].value) << s.name << " [" << back[i].section << "] " << k.key;
      }
  }
  // The structs' own INI writers give the same texts (slamOptionsIni, topologyOptionsIni are what apps write).
  slam::SlamOptions o;
  o.particles = 17;
  o.resolution = 0.1 + 0.2;
  mrpt::config::CConfigFileMemory c;
  c.setContent(slam::slamOptionsIni(o));
  slam::SlamOptions b;
  b.loadFromConfigFile(c, "slam");
  EXPECT_EQ(b.resolution, o.resolution);
  EXPECT_EQ(slam::slamOptionsIni(b), slam::slamOptionsIni(o));
}

TEST(OptionSchemas, EveryValueOutOfItsRangeIsRefusedWithSectionAndKey) {
  std::size_t checked = 0;
  for (const Subject& s : subjects())
    for (const auto& section : s.defaults())
      for (const auto& k : section.keys)
        for (const auto& v : outOfRange(k)) {
          mrpt::config::CConfigFileMemory cfg;
          cfg.write(section.section, k.key, v);
          try {
            s.load(cfg);
            ADD_FAILURE() << s.name << ": [" << section.section << "] " << k.key << " = " << v << " accepted (range "
                          << k.range << ")";
          } catch (const InputError& e) {
            EXPECT_EQ(e.field(), "[" + section.section + "] " + k.key) << e.what();
            EXPECT_NE(e.message().find("must be"), std::string::npos) << e.what();
            ++checked;
          }
        }
  // SlamOptions has 54 keys with a range, TopologyOptions 30, the training INI's three tables 17, [relations_metric]
  // 1: both ends of the closed ones count twice.
  EXPECT_GE(checked, 130u);
}

// --help-options of the apps whose run is an INI or that read an options INI: exit 0 (also without the arguments a run needs), and the
// text of the tables: every key of every section on a line "  key = default".
TEST(OptionSchemas, AppsListEveryKeyWithHelpOptions) {
  struct App {
    const char* name;
    std::string help;
    std::vector<OptionSection> sections;
  };
  std::vector<OptionSection> map_sections = {{"map_run", mapping::mapRunSchema().describe({})},
                                             {"slam", slam::slamOptionSchema().describe({})}};
  for (const auto& s : topology::describeTopologyOptions({})) map_sections.push_back(s);
  map_sections.push_back({mapping::kTopologyBuilderSection, mapping::topologyBuilderOptionSchema().describe({})});
  std::vector<OptionSection> topology_sections = {{"topology_run", topology::topologyRunSchema().describe({})}};
  for (const auto& s : topology::describeTopologyOptions({})) topology_sections.push_back(s);
  const std::vector<App> apps = {
      {"gridtopo-slam", slam::slamOptionsHelp(),
       {{"slam_run", slam::slamRunSchema().describe({})}, {"slam", slam::slamOptionSchema().describe({})}}},
      {"gridtopo-topology", topology::topologyRunOptionsHelp(), topology_sections},
      {"gridtopo-map", mapping::mapRunOptionsHelp(), map_sections},
      {"gridtopo-train", places::trainingOptionsHelp(),
       {{"scan_simulation", places::scanSimulationOptionSchema().describe({})},
        {"features", places::featureOptionSchema().describe({})},
        {"training", places::trainingOptionSchema().describe({})}}},
      {"gridtopo-eval", eval::relationsMetricOptionsHelp(),
       {{"relations_metric", eval::relationsMetricOptionSchema().describe({})}}},
  };
  for (const App& app : apps) {
    const auto r = testing_app::runApp(app.name, "--help-options");
    EXPECT_EQ(r.status, 0) << app.name << ": " << r.output;
    EXPECT_EQ(r.output, app.help) << app.name;
    std::size_t keys = 0;
    for (const auto& s : app.sections) {
      EXPECT_NE(r.output.find("[" + s.section + "]\n"), std::string::npos) << app.name << " [" << s.section << "]";
      for (const auto& k : s.keys) {
        EXPECT_NE(r.output.find("\n  " + k.key + " = " + k.default_shown), std::string::npos)
            << app.name << " [" << s.section << "] " << k.key;
        ++keys;
      }
    }
    EXPECT_GT(keys, 3u) << app.name;
  }
  // The slam table's one-line help and range, as the user reads them.
  EXPECT_NE(slam::slamOptionsHelp().find("\n  particles = 30 "), std::string::npos);
  EXPECT_NE(slam::slamOptionsHelp().find("(int [1, 100000]) number of particles\n"), std::string::npos);
}
