#include "gridtopo/experiment/experiment_spec.h"

#include <filesystem>
#include <algorithm>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_value.h"

namespace fs = std::filesystem;

namespace gridtopo::experiment {
namespace {

/// One key of a section as read: its section, key, value (comment removed) and line.
struct Entry {
  std::string section, key, value;
  std::size_t line = 0;
};

std::vector<Entry> entriesOf(const IniFile& doc, const std::string& section) {
  std::vector<Entry> out;
  for (const auto& k : doc.keys(section)) out.push_back({section, k, *doc.value(section, k), doc.line(section, k)});
  return out;
}

std::string field(const Entry& e) { return "[" + e.section + "] " + e.key; }

[[noreturn]] void unknownKey(const IniFile& doc, const Entry& e, const std::string& known) {
  throw InputError(doc.name(), e.line, field(e), "unknown key (expected one of: " + known + ")");
}

std::string resolve(const IniFile& doc, const std::string& p) {
  if (p.empty()) return p;
  if (fs::path(p).is_absolute()) return fs::path(p).lexically_normal().string();
  return fs::absolute(fs::path(doc.name()).parent_path() / p).lexically_normal().string();
}

std::string existingFile(const IniFile& doc, const Entry& e) {
  const std::string p = resolve(doc, e.value);
  if (e.value.empty()) throw InputError(doc.name(), e.line, field(e), "empty path");
  if (!fs::is_regular_file(p)) throw InputError(doc.name(), e.line, field(e), "no such file: " + p);
  return p;
}

}  // namespace

const char* toString(SuccessMetric m) {
  switch (m) {
    case SuccessMetric::TransMean: return "trans_mean";
    case SuccessMetric::TransMax: return "trans_max";
    case SuccessMetric::RotMean: return "rot_mean";
    case SuccessMetric::RotMax: return "rot_max";
  }
  return "?";
}

bool isTopologyKey(const std::string& k) {
  for (const char* s : kTopologySections)
    if (k.rfind(std::string(s) + ".", 0) == 0) return true;
  return false;
}

bool ExperimentSpec::topologyRuns() const {
  if (!topology_ini.empty() || !topology.empty()) return true;
  for (const auto& k : sweep)
    if (isTopologyKey(k.key)) return true;
  return false;
}

const DatasetSpec* ExperimentSpec::dataset(const std::string& n) const {
  for (const auto& d : datasets)
    if (d.name == n) return &d;
  return nullptr;
}

ExperimentSpec parseExperimentSpec(const IniFile& doc) {
  doc.requireNoRepeats();
  ExperimentSpec spec;
  spec.path = doc.name();
  spec.name = fs::path(doc.name()).stem().string();
  for (const auto& section : doc.sections()) {
    const std::size_t section_line = doc.line(section);
    const std::vector<Entry> entries = entriesOf(doc, section);
    if (section == "experiment") {
      for (const auto& e : entries) {
        if (e.key == "name") {
          if (e.value.empty() || e.value.find_first_of(" \t/'\"") != std::string::npos)
            throw InputError(doc.name(), e.line, field(e), "a name without blanks, quotes or '/'");
          spec.name = e.value;
        } else if (e.key == "description") {
          spec.description = e.value;
        } else if (e.key == "output") {
          if (e.value.empty()) throw InputError(doc.name(), e.line, field(e), "empty path");
          spec.output = resolve(doc, e.value);
        } else if (e.key == "base_ini") {
          spec.base_ini = existingFile(doc, e);
        } else if (e.key == "base_section") {
          if (e.value.empty()) throw InputError(doc.name(), e.line, field(e), "empty section name");
          spec.base_section = e.value;
        } else if (e.key == "topology_ini") {
          spec.topology_ini = existingFile(doc, e);
        } else if (e.key == "places_model") {
          spec.places_model = existingFile(doc, e);
        } else {
          unknownKey(doc, e, "name, description, output, base_ini, base_section, topology_ini, places_model");
        }
      }
    } else if (section == "record") {
      for (const auto& e : entries) {
        if (e.key == "success_metric") {
          bool found = false;
          for (auto m : {SuccessMetric::TransMean, SuccessMetric::TransMax, SuccessMetric::RotMean,
                         SuccessMetric::RotMax})
            if (e.value == toString(m)) spec.success_metric = m, found = true;
          if (!found)
            throw InputError(doc.name(), e.line, field(e),
                             "unknown value '" + e.value + "' (expected trans_mean, trans_max, rot_mean or rot_max)");
        } else if (e.key == "success_threshold") {
          if (auto what = parseIniValue(e.value, spec.success_threshold))
            throw InputError(doc.name(), e.line, field(e), "cannot parse '" + e.value + "' as " + *what);
          if (!(spec.success_threshold > 0)) throw InputError(doc.name(), e.line, field(e), "must be > 0");
        } else if (e.key == "keep_maps") {
          if (auto what = parseIniValue(e.value, spec.keep_maps))
            throw InputError(doc.name(), e.line, field(e), "cannot parse '" + e.value + "' as " + *what);
        } else if (e.key == "plots") {
          spec.plots.clear();
          std::istringstream in(e.value);
          std::string p;
          while (in >> p) {
            if (p == "none") continue;
            if (p != "error" && p != "success" && p != "time" && p != "neff")
              throw InputError(doc.name(), e.line, field(e),
                               "unknown plot '" + p + "' (expected error, success, time, neff or none)");
            spec.plots.push_back(p);
          }
        } else {
          unknownKey(doc, e, "success_metric, success_threshold, keep_maps, plots");
        }
      }
    } else if (section.rfind("dataset.", 0) == 0) {
      DatasetSpec d;
      d.name = section.substr(8);
      d.line = section_line;
      if (d.name.empty() || d.name.find_first_of(" \t/'\"") != std::string::npos)
        throw InputError(doc.name(), section_line, "[" + section + "]", "a dataset name without blanks, quotes or '/'");
      for (const auto& e : entries) {
        if (e.key == "log") d.log = existingFile(doc, e);
        else if (e.key == "relations") d.relations = existingFile(doc, e);
        else if (e.key == "map") d.map = existingFile(doc, e);
        else if (e.key == "plan") d.plan = existingFile(doc, e);
        else if (e.key == "plan_labels") d.plan_labels = existingFile(doc, e);
        else if (e.key == "plan_segmentation") d.plan_segmentation = existingFile(doc, e);
        else unknownKey(doc, e, "log, relations, map, plan, plan_labels, plan_segmentation");
      }
      if (d.log.empty() && d.map.empty())
        throw InputError(doc.name(), section_line, "[" + section + "] log", "missing: the dataset's log");
      if (!d.log.empty() && !d.map.empty())
        throw InputError(doc.name(), doc.line(section, "map"), "[" + section + "] map",
                         "give a log (topology runs on the SLAM run's map) or a map, not both");
      const int plan_keys = !d.plan.empty() + !d.plan_labels.empty() + !d.plan_segmentation.empty();
      if (plan_keys != 0 && plan_keys != 3)
        for (const char* k : {"plan", "plan_labels", "plan_segmentation"})
          if (!doc.hasKey(section, k))
            throw InputError(doc.name(), section_line, "[" + section + "] " + k,
                             "missing: a labelled plan needs plan, plan_labels and plan_segmentation");
      spec.datasets.push_back(d);
    } else if (section == "slam") {
      for (const auto& e : entries) spec.slam.push_back({e.key, e.value, e.line});
    } else if (section == "topology" || section == "relaxation" || section == "correction") {
      for (const auto& e : entries) spec.topology.push_back({section, e.key, e.value, e.line});
    } else if (section == "sweep") {
      for (const auto& e : entries) {
        if (e.key == "zip") {
          std::istringstream groups(e.value);
          std::string g;
          while (std::getline(groups, g, ',')) {
            std::istringstream keys(g);
            std::vector<std::string> group;
            std::string k;
            while (keys >> k) group.push_back(k);
            spec.zip_groups.push_back(group);
          }
          continue;
        }
        try {
          spec.sweep.push_back({e.key, parseSweepValues(e.value), e.line});
        } catch (const std::invalid_argument& err) {
          throw InputError(doc.name(), e.line, field(e), err.what());
        }
      }
    } else {
      throw InputError(doc.name(), section_line, "[" + section + "]",
                       "unknown section (expected [experiment], [record], [dataset.NAME], [slam], [topology], [relaxation], "
                       "[correction], [sweep])");
    }
  }
  if (spec.datasets.empty())
    throw InputError(doc.name(), 0, "[dataset.NAME]", "no dataset: add a [dataset.NAME] section with log = ...");
  for (const auto& k : spec.sweep) {
    if (k.key == "dataset") {
      for (const auto& v : k.values)
        if (!spec.dataset(v))
          throw InputError(doc.name(), k.line, "[sweep] dataset", "no section [dataset." + v + "]");
    } else if (k.key == "max_scans") {
      for (const auto& v : k.values) {
        long n = 0;
        if (parseIniValue(v, n) || n < 1)
          throw InputError(doc.name(), k.line, "[sweep] max_scans", "'" + v + "' is not a positive integer");
      }
    }
  }
  if (!spec.topologyRuns())
    for (const auto& d : spec.datasets)
      if (d.log.empty())
        throw InputError(doc.name(), doc.line("dataset." + d.name, "map"), "[dataset." + d.name + "] map",
                         "a map without a log needs topology runs (topology_ini, a [topology] section or a swept "
                         "topology.KEY)");
  if (spec.topologyRuns() && spec.places_model.empty())
    throw InputError(doc.name(), doc.line("experiment"), "[experiment] places_model",
                     "missing: topology runs need the place model (e.g. datasets/models/places_model.yml)");
  // A crossed key lists each value once (a key in a zip group may repeat values: its tuples must be distinct).
  for (const auto& k : spec.sweep) {
    bool zipped = false;
    for (const auto& g : spec.zip_groups) zipped = zipped || std::find(g.begin(), g.end(), k.key) != g.end();
    if (zipped) continue;
    try {
      checkDistinct(k.values);
    } catch (const std::invalid_argument& err) {
      throw InputError(doc.name(), k.line, "[sweep] " + k.key, err.what());
    }
  }
  try {
    expandSweep(spec.sweep, spec.zip_groups);  // zip groups: known keys, equal lengths, distinct tuples
  } catch (const std::invalid_argument& err) {
    throw InputError(doc.name(), doc.line("sweep", "zip"), "[sweep] zip", err.what());
  }
  return spec;
}

ExperimentSpec loadExperimentSpec(const std::string& path) { return parseExperimentSpec(IniFile::read(path)); }

}  // namespace gridtopo::experiment
