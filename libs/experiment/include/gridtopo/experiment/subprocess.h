#pragma once
// Child processes of the experiment runner: one gridtopo-slam run (or gnuplot) with its output in a log file, its
// exit status or the signal that ended it, and from wait4's rusage its CPU time and peak RSS. A child dies with
// the runner (PR_SET_PDEATHSIG), so a killed runner leaves no orphan writing into a run folder.
#include <sys/types.h>

#include <string>
#include <vector>

namespace gridtopo::experiment {

struct ProcessResult {
  int exit_code = -1;  ///< -1 when ended by a signal
  int signal = 0;      ///< the signal that ended it, 0 when it exited
  double wall_s = 0, cpu_s = 0;  ///< cpu = user + system
  double peak_rss_mb = 0;        ///< ru_maxrss
  bool ok() const { return exit_code == 0; }
};

/// Starts argv[0] (a path) with `argv`, stdout and stderr appended to `log_path` ("" = inherited), in `cwd` ("" =
/// the current one), stdin from /dev/null. Throws std::runtime_error when fork fails; an exec failure shows as
/// exit code 127 with the reason in the log.
pid_t spawnProcess(const std::vector<std::string>& argv, const std::string& log_path, const std::string& cwd = "");

/// wait4 on `pid` (or any child for -1); `block` false returns 0 when none has ended. Fills `result` (wall time
/// excluded: the caller knows when it started). Returns the pid reaped.
pid_t reapChild(pid_t pid, bool block, ProcessResult& result);

/// spawnProcess then wait: the whole result, wall time included.
ProcessResult runProcess(const std::vector<std::string>& argv, const std::string& log_path, const std::string& cwd = "");

/// A word for a POSIX shell: unchanged when made of safe characters, else in single quotes.
std::string shellQuote(const std::string& s);

/// The last non-empty line of a text file containing "error" (else the last non-empty line), for a failed run's record.
std::string lastErrorLine(const std::string& path);

}  // namespace gridtopo::experiment
