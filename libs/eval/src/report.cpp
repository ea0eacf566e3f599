#include "gridtopo/eval/report.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "gridtopo/core/option_schema.h"
#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::eval {
namespace {

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string line(const char* name, const ErrorStats& s, const char* unit, int digits) {
  return std::string(name) + fixed(s.mean, digits) + " ± " + fixed(s.std, digits) + " " + unit + "   (min " +
         fixed(s.min, digits) + ", max " + fixed(s.max, digits) + ", n = " + std::to_string(s.count) + ")\n";
}

std::string jsonNumber(double v) { return std::isfinite(v) ? io::formatDouble(v) : "null"; }

std::string jsonStats(const ErrorStats& s) {
  return "{\"mean\": " + jsonNumber(s.mean) + ", \"std\": " + (s.count > 1 ? jsonNumber(s.std) : "null") +
         ", \"min\": " + jsonNumber(s.min) + ", \"max\": " + jsonNumber(s.max) +
         ", \"count\": " + std::to_string(s.count) + "}";
}

// "0.0160 m (n=1773), 0.55 deg", or "none (n=0)" for an empty subset.
std::string splitText(const RelationsSplit& s) {
  if (s.translational.count == 0) return "none (n=0)";
  return fixed(s.translational.mean, 4) + " m (n=" + std::to_string(s.translational.count) + "), " +
         fixed(s.rotational.mean, 2) + " deg";
}

// An empty side has no figures: null, not the zeros of an empty ErrorStats.
std::string jsonSplitStats(const ErrorStats& s) {
  return s.count == 0 ? "{\"mean\": null, \"std\": null, \"min\": null, \"max\": null, \"count\": 0}" : jsonStats(s);
}

std::string jsonSplit(const RelationsSplit& s) {
  return "{\"count\": " + std::to_string(s.translational.count) + ", \"translational_m\": " +
         jsonSplitStats(s.translational) + ", \"rotational_deg\": " + jsonSplitStats(s.rotational) + "}";
}

}  // namespace

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string formatSummary(const RelationsResult& r) {
  std::string s;
  s += line("translational error:   ", r.translational, "m", 4);
  s += line("translational squared: ", r.translational_squared, "m²", 4);
  s += line("rotational error:      ", r.rotational, "deg", 3);
  s += line("rotational squared:    ", r.rotational_squared, "deg²", 3);
  s += "relation endpoints: " + std::to_string(r.endpoints_direct) + " with an estimate in reach, " +
       std::to_string(r.endpoints_corrected) + " corrected by odometry";
  if (r.endpoints_interpolated)
    s += ", " + std::to_string(r.endpoints_interpolated) + " interpolated between estimates";
  if (r.endpoints_uncorrected) s += ", " + std::to_string(r.endpoints_uncorrected) + " UNCORRECTED (no odometry)";
  s += "; largest time gap " + fixed(r.max_gap, 3) + " s\n";
  const std::string span = shortestText(r.revisit_span);
  s += "local (|t2-t1| <= " + span + " s): " + splitText(r.local) + "; revisits (> " + span +
       " s): " + splitText(r.revisit) + "\n";
  return s;
}

std::string formatJson(const RelationsResult& r, const std::vector<std::pair<std::string, std::string>>& info,
                       const std::vector<std::pair<std::string, double>>& numbers,
                       const std::vector<std::pair<std::string, bool>>& flags) {
  std::set<std::string> keys = {"translational_m", "translational_squared_m2", "rotational_deg",
                                "rotational_squared_deg2", "endpoints_direct", "endpoints_corrected",
                                "endpoints_interpolated", "endpoints_uncorrected", "revisit_span_s", "local",
                                "revisit", "largest_time_gap_s"};
  auto once = [&](const std::string& k) {
    if (!keys.insert(k).second) throw std::invalid_argument("formatJson: the key '" + k + "' is given twice");
  };
  std::string s = "{\n";
  for (const auto& [k, v] : info) once(k), s += "  " + jsonString(k) + ": " + jsonString(v) + ",\n";
  for (const auto& [k, v] : flags) once(k), s += "  " + jsonString(k) + ": " + (v ? "true" : "false") + ",\n";
  for (const auto& [k, v] : numbers) once(k), s += "  " + jsonString(k) + ": " + jsonNumber(v) + ",\n";
  s += "  \"translational_m\": " + jsonStats(r.translational) + ",\n";
  s += "  \"translational_squared_m2\": " + jsonStats(r.translational_squared) + ",\n";
  s += "  \"rotational_deg\": " + jsonStats(r.rotational) + ",\n";
  s += "  \"rotational_squared_deg2\": " + jsonStats(r.rotational_squared) + ",\n";
  s += "  \"endpoints_direct\": " + std::to_string(r.endpoints_direct) + ",\n";
  s += "  \"endpoints_corrected\": " + std::to_string(r.endpoints_corrected) + ",\n";
  s += "  \"endpoints_interpolated\": " + std::to_string(r.endpoints_interpolated) + ",\n";
  s += "  \"endpoints_uncorrected\": " + std::to_string(r.endpoints_uncorrected) + ",\n";
  s += "  \"revisit_span_s\": " + jsonNumber(r.revisit_span) + ",\n";
  s += "  \"local\": " + jsonSplit(r.local) + ",\n";
  s += "  \"revisit\": " + jsonSplit(r.revisit) + ",\n";
  s += "  \"largest_time_gap_s\": " + jsonNumber(r.max_gap) + "\n";
  return s + "}\n";
}

std::string formatErrors(const RelationsResult& r) {
  std::string s = "# t1 t2 translational_error_m rotational_error_deg gap1_s gap2_s (relations file order)\n";
  for (const auto& e : r.errors) {
    s += io::formatDouble(e.relation.t1) + ' ' + io::formatDouble(e.relation.t2) + ' ' +
         io::formatDouble(e.translational) + ' ' + io::formatDouble(e.rotational * 180.0 / M_PI) + ' ' +
         io::formatDouble(e.gap1) + ' ' + io::formatDouble(e.gap2) + '\n';
  }
  return s;
}

}  // namespace gridtopo::eval
