#include "gridtopo/core/ini_value.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace gridtopo {

std::string iniValueText(const std::string& raw) {
  std::string s = raw;
  // A comment starts at ';', '#' or "//" that is at the beginning or follows white space.
  for (std::size_t i = 0; i < s.size(); ++i) {
    const bool at_word_start = i == 0 || std::isspace(static_cast<unsigned char>(s[i - 1]));
    if (!at_word_start) continue;
    if (s[i] == ';' || s[i] == '#' || (s[i] == '/' && i + 1 < s.size() && s[i + 1] == '/')) {
      s.resize(i);
      break;
    }
  }
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

namespace {

template <class T>
std::optional<std::string> parseInteger(const std::string& text, T& out) {
  const char* expected = std::numeric_limits<T>::is_signed ? "an integer" : "a non-negative integer";
  if (text.empty()) return std::string(expected);
  if (!std::numeric_limits<T>::is_signed && text[0] == '-') return std::string(expected);
  errno = 0;
  char* end = nullptr;
  if constexpr (std::numeric_limits<T>::is_signed) {
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (errno != 0 || end != text.c_str() + text.size() || v < std::numeric_limits<T>::min() ||
        v > std::numeric_limits<T>::max())
      return std::string(expected);
    out = static_cast<T>(v);
  } else {
    const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
    if (errno != 0 || end != text.c_str() + text.size() || v > std::numeric_limits<T>::max())
      return std::string(expected);
    out = static_cast<T>(v);
  }
  return std::nullopt;
}

template <class T>
std::optional<std::string> parseReal(const std::string& text, T& out) {
  if (text.empty()) return std::string("a number");
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v) || errno == ERANGE) return std::string("a finite number");
  if (std::abs(v) > static_cast<double>(std::numeric_limits<T>::max())) return std::string("a finite number");
  out = static_cast<T>(v);
  return std::nullopt;
}

}  // namespace

std::optional<std::string> parseIniValue(const std::string& text, int& out) { return parseInteger(text, out); }
std::optional<std::string> parseIniValue(const std::string& text, unsigned& out) { return parseInteger(text, out); }
std::optional<std::string> parseIniValue(const std::string& text, long& out) { return parseInteger(text, out); }
std::optional<std::string> parseIniValue(const std::string& text, unsigned long& out) {
  return parseInteger(text, out);
}
std::optional<std::string> parseIniValue(const std::string& text, double& out) { return parseReal(text, out); }
std::optional<std::string> parseIniValue(const std::string& text, float& out) { return parseReal(text, out); }

std::optional<std::string> parseIniValue(const std::string& text, bool& out) {
  std::string t;
  for (char c : text) t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (t == "true" || t == "1" || t == "yes" || t == "on") {
    out = true;
    return std::nullopt;
  }
  if (t == "false" || t == "0" || t == "no" || t == "off") {
    out = false;
    return std::nullopt;
  }
  return std::string("a boolean (true/false)");
}

std::optional<std::string> parseIniValue(const std::string& text, std::string& out) {
  out = text;
  return std::nullopt;
}

std::string iniText(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

std::string iniText(int v) { return std::to_string(v); }

std::string iniText(bool v) { return v ? "true" : "false"; }

std::string iniText(const std::string& v) { return v; }

}  // namespace gridtopo
