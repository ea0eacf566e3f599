#include "gridtopo/slam/slam_run_ini.h"

#include <mrpt/config/CConfigFile.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"
#include "gridtopo/core/ini_value.h"
#include "gridtopo/slam/options_ini.h"

namespace fs = std::filesystem;

namespace gridtopo::slam {

const OptionSchema<SlamRunSpec>& slamRunSchema() {
  using S = SlamRunSpec;
  static const OptionSchema<S> schema =
      OptionSchema<S>("gridtopo::slam::SlamRunSpec")
          .add("input", &S::input, OptionRange::any(), "", "the log: CARMEN (.clf, .log, optionally .gz) or MRPT rawlog")
          .add("output", &S::output, OptionRange::any(), "", "the output directory")
          .add("max_scans", &S::max_scans, OptionRange::any(), "scans", "feed only the first max_scans scans; 0 = all");
  return schema;
}

std::vector<std::string> slamOptionKeys() { return slamOptionSchema().keys(); }

std::string slamOptionsHelp() {
  return optionsHelp(kSlamRunSection, slamRunSchema().describe(SlamRunSpec())) + "\n" +
         optionsHelp("slam", slamOptionSchema().describe(SlamOptions()));
}

namespace {

/// Loads the options of `section` from `path`, naming the line of the key in the error when the INI has it.
SlamOptions loadOptions(const std::string& path, const IniFile& layout, const std::string& section) {
  SlamOptions o;
  try {
    o.loadFromConfigFile(mrpt::config::CConfigFile(path), section);
  } catch (const InputError& e) {
    throw layout.withLine(e);  // SlamOptions names "[section] key" without the line
  }
  return o;
}

std::string absolute(const std::string& p) { return fs::absolute(fs::path(p)).lexically_normal().string(); }

}  // namespace

SlamRunSpec loadSlamRunIni(const std::string& path, const std::string& options_section) {
  if (!fs::is_regular_file(path)) throw InputError(path, "no such INI file");
  const IniFile ini = IniFile::read(path);
  ini.requireKnownSections({kSlamRunSection, options_section});
  ini.requireKnownKeys(kSlamRunSection, slamRunSchema().keys());
  ini.requireKnownKeys(options_section, slamOptionKeys(), "not an option of the filter; see config-ini/slam.ini");
  SlamRunSpec spec;
  spec.ini = path;
  const std::string run = kSlamRunSection;
  if (const auto v = ini.value(run, "input"); v && !v->empty()) {
    spec.input = *v;
    spec.input_from_ini = true;
  }
  if (const auto v = ini.value(run, "output"); v && !v->empty()) {
    spec.output = *v;
    spec.output_from_ini = true;
  }
  unsigned long max_scans = 0;
  if (ini.parseValue(run, "max_scans", max_scans)) spec.max_scans = max_scans;
  spec.options = loadOptions(path, ini, options_section);
  return spec;
}

SlamOptions loadSlamOptionsIni(const std::string& path, const std::string& section) {
  if (!fs::is_regular_file(path)) throw InputError(path, "no such INI file");
  const IniFile ini = IniFile::read(path);
  if (!ini.hasSection(section)) throw InputError(path, 0, "[" + section + "]", "section not found");
  return loadOptions(path, ini, section);
}

void overrideOptions(SlamOptions& o, const SlamOptionFlags& f) {
  const std::string cli = "<command line>";
  if (f.particles) o.particles = *f.particles;
  if (f.seed) {
    if (*f.seed < 0) throw InputError(cli, 0, "--seed", "must be >= 0");
    o.seed = static_cast<std::uint64_t>(*f.seed);
  }
  if (f.threads) o.threads = *f.threads;
  if (f.proposal) {
    try {
      o.proposal.type = proposalFromString(*f.proposal);
    } catch (const std::invalid_argument& e) {
      throw InputError(cli, 0, "--proposal", e.what());
    }
  }
  o.validate(cli, "slam");
}

void checkSlamRunSpec(const SlamRunSpec& spec) {
  const std::string run = kSlamRunSection;
  auto lineOf = [&](const std::string& key) {
    return spec.ini.empty() ? std::size_t{0} : IniFile::read(spec.ini).lineOrSection(run, key);
  };
  if (spec.input.empty())
    throw InputError(spec.ini.empty() ? "<command line>" : spec.ini, lineOf("input"), "[" + run + "] input",
                     "missing: name the log to read (or give -i)");
  if (spec.output.empty())
    throw InputError(spec.ini.empty() ? "<command line>" : spec.ini, lineOf("output"), "[" + run + "] output",
                     "missing: name the output directory (or give -o)");
  if (!fs::exists(spec.input)) {
    if (spec.input_from_ini)
      throw InputError(spec.ini, lineOf("input"), "[" + run + "] input", "no such file '" + spec.input + "'");
    throw InputError(spec.input, "no such file");
  }
}

std::string slamRunIni(const SlamRunSpec& spec) {
  SlamRunSpec run = spec;
  run.input = absolute(spec.input);
  run.output = absolute(spec.output);
  return slamRunSchema().ini(run, kSlamRunSection) + "\n" + slamOptionsIni(spec.options, "slam");
}

}  // namespace gridtopo::slam
