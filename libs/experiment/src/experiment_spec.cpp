#include "gridtopo/experiment/experiment_spec.h"

#include <filesystem>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_value.h"

namespace fs = std::filesystem;

namespace gridtopo::experiment {
namespace {

std::string field(const IniSection& s, const IniEntry& e) { return "[" + s.name + "] " + e.key; }

[[noreturn]] void unknownKey(const IniDocument& doc, const IniSection& s, const IniEntry& e,
                             const std::string& known) {
  throw InputError(doc.path, e.line, field(s, e), "unknown key (expected one of: " + known + ")");
}

std::string resolve(const IniDocument& doc, const std::string& p) {
  if (p.empty()) return p;
  if (fs::path(p).is_absolute()) return fs::path(p).lexically_normal().string();
  return fs::absolute(fs::path(doc.path).parent_path() / p).lexically_normal().string();
}

std::string existingFile(const IniDocument& doc, const IniSection& s, const IniEntry& e) {
  const std::string p = resolve(doc, e.value);
  if (e.value.empty()) throw InputError(doc.path, e.line, field(s, e), "empty path");
  if (!fs::is_regular_file(p)) throw InputError(doc.path, e.line, field(s, e), "no such file: " + p);
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

const DatasetSpec* ExperimentSpec::dataset(const std::string& n) const {
  for (const auto& d : datasets)
    if (d.name == n) return &d;
  return nullptr;
}

ExperimentSpec parseExperimentSpec(const IniDocument& doc) {
  ExperimentSpec spec;
  spec.path = doc.path;
  spec.name = fs::path(doc.path).stem().string();
  for (const auto& s : doc.sections) {
    if (s.name == "experiment") {
      for (const auto& e : s.entries) {
        if (e.key == "name") {
          if (e.value.empty() || e.value.find_first_of(" \t/'\"") != std::string::npos)
            throw InputError(doc.path, e.line, field(s, e), "a name without blanks, quotes or '/'");
          spec.name = e.value;
        } else if (e.key == "description") {
          spec.description = e.value;
        } else if (e.key == "output") {
          if (e.value.empty()) throw InputError(doc.path, e.line, field(s, e), "empty path");
          spec.output = resolve(doc, e.value);
        } else if (e.key == "base_ini") {
          spec.base_ini = existingFile(doc, s, e);
        } else if (e.key == "base_section") {
          if (e.value.empty()) throw InputError(doc.path, e.line, field(s, e), "empty section name");
          spec.base_section = e.value;
        } else {
          unknownKey(doc, s, e, "name, description, output, base_ini, base_section");
        }
      }
    } else if (s.name == "record") {
      for (const auto& e : s.entries) {
        if (e.key == "success_metric") {
          bool found = false;
          for (auto m : {SuccessMetric::TransMean, SuccessMetric::TransMax, SuccessMetric::RotMean,
                         SuccessMetric::RotMax})
            if (e.value == toString(m)) spec.success_metric = m, found = true;
          if (!found)
            throw InputError(doc.path, e.line, field(s, e),
                             "unknown value '" + e.value + "' (expected trans_mean, trans_max, rot_mean or rot_max)");
        } else if (e.key == "success_threshold") {
          if (auto what = parseIniValue(e.value, spec.success_threshold))
            throw InputError(doc.path, e.line, field(s, e), "cannot parse '" + e.value + "' as " + *what);
          if (!(spec.success_threshold > 0)) throw InputError(doc.path, e.line, field(s, e), "must be > 0");
        } else if (e.key == "keep_maps") {
          if (auto what = parseIniValue(e.value, spec.keep_maps))
            throw InputError(doc.path, e.line, field(s, e), "cannot parse '" + e.value + "' as " + *what);
        } else if (e.key == "plots") {
          spec.plots.clear();
          std::istringstream in(e.value);
          std::string p;
          while (in >> p) {
            if (p == "none") continue;
            if (p != "error" && p != "success" && p != "time" && p != "neff")
              throw InputError(doc.path, e.line, field(s, e),
                               "unknown plot '" + p + "' (expected error, success, time, neff or none)");
            spec.plots.push_back(p);
          }
        } else {
          unknownKey(doc, s, e, "success_metric, success_threshold, keep_maps, plots");
        }
      }
    } else if (s.name.rfind("dataset.", 0) == 0) {
      DatasetSpec d;
      d.name = s.name.substr(8);
      d.line = s.line;
      if (d.name.empty() || d.name.find_first_of(" \t/'\"") != std::string::npos)
        throw InputError(doc.path, s.line, "[" + s.name + "]", "a dataset name without blanks, quotes or '/'");
      for (const auto& e : s.entries) {
        if (e.key == "log") d.log = existingFile(doc, s, e);
        else if (e.key == "relations") d.relations = existingFile(doc, s, e);
        else unknownKey(doc, s, e, "log, relations");
      }
      if (d.log.empty()) throw InputError(doc.path, s.line, "[" + s.name + "] log", "missing: the dataset's log");
      spec.datasets.push_back(d);
    } else if (s.name == "slam") {
      spec.slam = s.entries;
    } else if (s.name == "sweep") {
      for (const auto& e : s.entries) {
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
          throw InputError(doc.path, e.line, field(s, e), err.what());
        }
      }
    } else {
      throw InputError(doc.path, s.line, "[" + s.name + "]",
                       "unknown section (expected [experiment], [record], [dataset.NAME], [slam], [sweep])");
    }
  }
  if (spec.datasets.empty())
    throw InputError(doc.path, 0, "[dataset.NAME]", "no dataset: add a [dataset.NAME] section with log = ...");
  const IniSection* sweep = doc.find("sweep");
  for (const auto& k : spec.sweep) {
    if (k.key == "dataset") {
      for (const auto& v : k.values)
        if (!spec.dataset(v))
          throw InputError(doc.path, k.line, "[sweep] dataset", "no section [dataset." + v + "]");
    } else if (k.key == "max_scans") {
      for (const auto& v : k.values) {
        long n = 0;
        if (parseIniValue(v, n) || n < 1)
          throw InputError(doc.path, k.line, "[sweep] max_scans", "'" + v + "' is not a positive integer");
      }
    }
  }
  try {
    expandSweep(spec.sweep, spec.zip_groups);  // zip groups: known keys, equal lengths
  } catch (const std::invalid_argument& err) {
    const IniEntry* zip = sweep ? sweep->find("zip") : nullptr;
    throw InputError(doc.path, zip ? zip->line : 0, "[sweep] zip", err.what());
  }
  return spec;
}

ExperimentSpec loadExperimentSpec(const std::string& path) { return parseExperimentSpec(readIniDocument(path)); }

}  // namespace gridtopo::experiment
