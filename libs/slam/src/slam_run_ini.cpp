#include "gridtopo/slam/slam_run_ini.h"

#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"
#include "gridtopo/core/run_args.h"
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
  ini.requireKnownSections({kSlamRunSection, options_section, LoopClosureOptions::kSection});
  ini.requireKnownKeys(kSlamRunSection, slamRunSchema().keys());
  ini.requireKnownKeys(options_section, slamOptionKeys(), "not an option of the filter; see config-ini/slam.ini");
  ini.requireKnownKeys(LoopClosureOptions::kSection, loopClosureOptionSchema().keys(),
                       "not an option of the loop closure; see config-ini/slam.ini");
  SlamRunSpec spec;
  spec.ini = path;
  slamRunSchema().loadRun(spec, spec.lines, ini, kSlamRunSection);
  spec.options = loadOptions(path, ini, options_section);
  return spec;
}

SlamOptions loadSlamOptionsIni(const std::string& path, const std::string& section) {
  if (!fs::is_regular_file(path)) throw InputError(path, "no such INI file");
  const IniFile ini = IniFile::read(path);
  ini.requireOptionsFile({section, LoopClosureOptions::kSection}, section);
  ini.requireKnownKeys(section, slamOptionKeys(), "not an option of the filter; see config-ini/slam.ini");
  ini.requireKnownKeys(LoopClosureOptions::kSection, loopClosureOptionSchema().keys(),
                       "not an option of the loop closure; see config-ini/slam.ini");
  return loadOptions(path, ini, section);
}

void overrideRun(SlamRunSpec& spec, const SlamRunFlags& f) {
  spec.lines.overrideWith(f.input, spec.input, "input");
  spec.lines.overrideWith(f.output, spec.output, "output");
  if (f.max_scans) spec.max_scans = static_cast<std::size_t>(std::max(0L, *f.max_scans));
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
  auto lineOf = [&](const std::string& key) { return spec.lines.of(key); };
  if (spec.input.empty())
    throw InputError(spec.ini.empty() ? "<command line>" : spec.ini, lineOf("input"), "[" + run + "] input",
                     "missing: name the log to read (or give -i)");
  if (spec.output.empty())
    throw InputError(spec.ini.empty() ? "<command line>" : spec.ini, lineOf("output"), "[" + run + "] output",
                     "missing: name the output directory (or give -o)");
  if (!fs::exists(spec.input)) {
    if (spec.fromIni("input"))
      throw InputError(spec.ini, lineOf("input"), "[" + run + "] input", "no such file '" + spec.input + "'");
    throw InputError(spec.input, "no such file");
  }
}

SlamRunSpec slamRunOfCommandLine(const std::string& run_ini, const std::optional<std::string>& config,
                                 const std::string& section, const SlamRunFlags& run, const SlamOptionFlags& options) {
  if (!run_ini.empty() && config) throw UsageError("give the options either in RUN.ini or with -c, not both");
  requireRunIniOrInputOutput(run_ini, run.input.has_value(), run.output.has_value());
  SlamRunSpec spec = run_ini.empty() ? SlamRunSpec{} : loadSlamRunIni(run_ini, section);
  if (config) spec.options = loadSlamOptionsIni(*config, section);
  overrideRun(spec, run);
  overrideOptions(spec.options, options);
  checkSlamRunSpec(spec);
  return spec;
}

std::string slamRunIni(const SlamRunSpec& spec) {
  SlamRunSpec run = spec;
  run.input = absolute(spec.input);
  run.output = absolute(spec.output);
  return slamRunSchema().ini(run, kSlamRunSection) + "\n" + slamOptionsIni(spec.options, "slam");
}

}  // namespace gridtopo::slam
