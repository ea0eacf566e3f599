#include "gridtopo/core/option_schema.h"

#include <mrpt/config/CConfigFile.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace gridtopo {

bool OptionRange::contains(double v) const {
  if (lo && (lo_open ? !(v > *lo) : !(v >= *lo))) return false;
  if (hi && (hi_open ? !(v < *hi) : !(v <= *hi))) return false;
  return std::isfinite(v);  // NaN and infinities lie in no range
}

std::string OptionRange::text() const {
  if (lo && hi)
    return std::string(lo_open ? "(" : "[") + shortestText(*lo) + ", " + shortestText(*hi) + (hi_open ? ")" : "]");
  if (lo) return std::string(lo_open ? "> " : ">= ") + shortestText(*lo);
  if (hi) return std::string(hi_open ? "< " : "<= ") + shortestText(*hi);
  return "";
}

std::size_t KeyLines::of(const std::string& key) const {
  const auto it = keys.find(key);
  return it != keys.end() ? it->second : section;
}

const char* toString(OptionType type) {
  switch (type) {
    case OptionType::Bool: return "bool";
    case OptionType::Int: return "int";
    case OptionType::Real: return "real";
    case OptionType::Text: return "text";
    case OptionType::Word: return "word";
  }
  return "?";
}

namespace {
// The shortest text that reads back to v at its own precision, without an exponent for everyday magnitudes
// (100000, not 1e+05).
template <class Real>
std::string shortest(Real v) {
  char buf[64];
  const bool fixed = v == 0 || (std::abs(v) >= Real(1e-4) && std::abs(v) < Real(1e15));
  const auto end = fixed ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed).ptr
                         : std::to_chars(buf, buf + sizeof buf, v).ptr;
  return std::string(buf, end);
}
}  // namespace

std::string shortestText(double v) { return shortest(v); }

std::string shortestText(float v) { return shortest(v); }

std::string iniFileName(const mrpt::config::CConfigFileBase& config) {
  if (const auto* f = dynamic_cast<const mrpt::config::CConfigFile*>(&config)) return f->getAssociatedFile();
  return "<ini>";
}

std::string optionsHelp(const std::string& section, const std::vector<OptionDescription>& keys) {
  std::vector<std::string> heads;
  std::size_t width = 0;
  for (const auto& k : keys) {
    heads.push_back(k.key + " = " + (k.default_shown.empty() ? k.default_value : k.default_shown));
    width = std::max(width, heads.back().size());
  }
  std::ostringstream out;
  out << "[" << section << "]\n";
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const OptionDescription& k = keys[i];
    const std::string& head = heads[i];
    std::string kind = toString(k.type);
    if (k.type == OptionType::Word) {
      kind.clear();
      for (const auto& w : k.words) kind += (kind.empty() ? "" : " | ") + w;
    }
    if (!k.range.empty()) kind += " " + k.range;
    if (!k.unit.empty()) kind += " " + k.unit;
    out << "  " << head << std::string(width > head.size() ? width - head.size() : 0, ' ') << "  (" << kind << ") "
        << k.help << "\n";
  }
  return out.str();
}

}  // namespace gridtopo
