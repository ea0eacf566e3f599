#pragma once
// A SLAM run as an INI file, in the spirit of MRPT's `rbpf-slam CONFIG.ini` (whose [MappingApplication] names the
// rawlog and the output directory): `gridtopo-slam RUN.ini` reads
//   [slam_run]  input = LOG, output = DIR, max_scans = N (0 = every scan)
//   [slam]      the filter's options (SlamOptions, config-ini/slam.ini)
// and the command-line flags override single values. A RUN.ini holds no other section and no unknown key (both are
// InputErrors naming the file, the line, the section and the key). The options.ini a run writes is this INI, with
// the paths absolute, so loading it again as RUN.ini (or its [slam] with -c) reproduces the run.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "gridtopo/slam/slam_options.h"

namespace gridtopo::slam {

inline constexpr const char* kSlamRunSection = "slam_run";

struct SlamRunSpec {
  std::string input;          ///< the log (CARMEN or MRPT rawlog); a relative path is taken from the working directory
  std::string output;         ///< the output directory (likewise)
  std::size_t max_scans = 0;  ///< feed only the first max_scans scans; 0 = every scan
  SlamOptions options;
  std::string ini;            ///< the RUN.ini this was read from; empty when none
  KeyLines lines;             ///< where [slam_run] and its keys stand in the RUN.ini (a flag's value has no line)

  /// `key`'s value is the RUN.ini's (no flag replaced it).
  bool fromIni(const std::string& key) const { return lines.has(key); }
};

/// The key table of [slam_run] (input, output, max_scans): its loading (OptionSchema::loadRun: an empty value leaves
/// the key unset, the lines are remembered), the strict check of its keys, its INI text, its help.
const OptionSchema<SlamRunSpec>& slamRunSchema();

/// The keys of the filter's options section ([slam]): slamOptionSchema's. For the strict checks of RUN.ini
/// files that hold a [slam] section (gridtopo-slam's, gridtopo-map's).
std::vector<std::string> slamOptionKeys();

/// `gridtopo-slam --help-options`: every key of [slam_run] and [slam] with its default, range, unit and help.
std::string slamOptionsHelp();

/// Reads a RUN.ini: [slam_run] and the options section `options_section` (either may be missing; the options
/// keep their defaults then). InputError for an unreadable file, another section, an unknown key or a bad value.
SlamRunSpec loadSlamRunIni(const std::string& path, const std::string& options_section = "slam");

/// The options of `section` of an options INI (`gridtopo-slam -c FILE`): InputError if the file or the section is
/// missing or a value is bad. Other sections are not read.
SlamOptions loadSlamOptionsIni(const std::string& path, const std::string& section = "slam");

/// The command line's values of the run (gridtopo-slam -i, -o, --max-scans); unset = keep.
struct SlamRunFlags {
  std::optional<std::string> input, output;
  std::optional<long> max_scans;  ///< 0 or less: every scan
};
/// Sets the given flags' values; a value a flag gives is no longer the RUN.ini's (fromIni).
void overrideRun(SlamRunSpec& spec, const SlamRunFlags& flags);

/// The command line's values of single options (gridtopo-slam -p, -s, -t, --proposal); unset = keep.
struct SlamOptionFlags {
  std::optional<int> particles;
  std::optional<long long> seed;
  std::optional<int> threads;
  std::optional<std::string> proposal;
};

/// Sets the given flags' values and validates the result: InputError("<command line>", 0, "--seed", ...) for a bad
/// flag, ("<command line>", 0, "[slam] key", ...) for options out of range.
void overrideOptions(SlamOptions& options, const SlamOptionFlags& flags);

/// Checks that the run names its input, which must exist, and its output. A missing or wrong value from a RUN.ini
/// is an InputError naming the RUN.ini, the line and "[slam_run] key"; a missing input given by -i names that file.
void checkSlamRunSpec(const SlamRunSpec& spec);

/// The run a command line names (gridtopo-slam): the RUN.ini `run_ini` (if not empty) with its options section
/// `section`, or the options INI `config` (-c), then the flags; checked (checkSlamRunSpec). UsageError for a RUN.ini
/// together with -c, or for neither a RUN.ini nor both -i and -o.
SlamRunSpec slamRunOfCommandLine(const std::string& run_ini, const std::optional<std::string>& config,
                                 const std::string& section, const SlamRunFlags& run, const SlamOptionFlags& options);

/// The exact loadable INI of the run: [slam_run] (input and output absolute, max_scans), then [slam] with every
/// option (slamOptionsIni).
std::string slamRunIni(const SlamRunSpec& spec);

}  // namespace gridtopo::slam
