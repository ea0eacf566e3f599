#include "gridtopo/eval/loop_closure_summary.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_value.h"
#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::eval {

std::optional<double> LoopClosureSummary::get(const std::string& key) const {
  for (const auto& [k, v] : values)
    if (k == key) return v;
  return std::nullopt;
}

std::optional<LoopClosureSummary> readLoopClosureSummary(const std::string& stats_path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(stats_path, ec)) return std::nullopt;
  std::ifstream in(stats_path);
  if (!in) throw InputError(stats_path, "cannot open the run's statistics");
  const std::string prefix = "# loop_closure:";
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.rfind(prefix, 0) != 0) continue;
    LoopClosureSummary s;
    s.path = stats_path;
    std::istringstream words(line.substr(prefix.size()));
    std::string key, value;
    while (words >> key) {
      if (!(words >> value)) throw InputError(stats_path, n, key, "a count without its value");
      double v = 0.0;
      if (parseIniValue(value, v)) throw InputError(stats_path, n, key, "expected a number, found '" + value + "'");
      for (const auto& [k, old] : s.values)
        if (k == key) throw InputError(stats_path, n, key, "given twice");
      s.values.emplace_back(key, v);
    }
    if (s.values.empty()) throw InputError(stats_path, n, "loop_closure", "the summary line holds no counts");
    return s;
  }
  return std::nullopt;
}

std::string statsBesideTrajectory(const std::string& trajectory_path) {
  return (std::filesystem::path(trajectory_path).parent_path() / "stats.txt").string();
}

std::string loopClosureSummaryText(const LoopClosureSummary& s) {
  std::ostringstream o;
  const auto count = [&](const char* key) { return static_cast<long long>(s.get(key).value_or(0.0)); };
  o << "loop closure (" << s.path << "): " << count("closures") << " accepted";
  if (s.get("global_accepted")) o << " (" << count("global_accepted") << " global)";
  o << ", " << count("rejected") << " switched off";
  if (const auto xy = s.get("largest_correction_xy"))
    o << ", largest correction " << io::formatDouble(*xy) << " m / "
      << io::formatDouble(s.get("largest_correction_theta").value_or(0.0)) << " rad";
  if (s.get("global_searches"))
    o << "; global search: " << count("global_searches") << " searches, "
      << (s.get("global_refuted") ? std::to_string(count("global_refuted")) + " refuted by what the place saw, " : "")
      << count("global_proposed") << " proposed"
      << (s.get("global_followed") ? " (" + std::to_string(count("global_followed")) + " followed)" : "") << ", "
      << count("global_contradicted") << " contradicted, " << count("global_dropped")
      << " dropped";
  o << "\n";
  return o.str();
}

}  // namespace gridtopo::eval
