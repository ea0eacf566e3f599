#pragma once
// Strict reading of INI values. MRPT's CConfigFileBase::read_int / read_double / read_bool convert with
// atoi / atof, so "abc" silently becomes 0 and "2.5" becomes 2 for an integer key; these helpers reject both
// with an InputError naming the section and the key. As in MRPT's INI files, a value may be followed by a
// comment after white space: "30 ; particles", "0.05 // metres", "true # on".
#include <optional>
#include <string>

#include "gridtopo/core/error.h"

namespace gridtopo {

/// The value part of an INI entry: surrounding white space and a trailing comment (white space, then ';', '#'
/// or "//") removed.
std::string iniValueText(const std::string& raw);

/// Parse `text` (already through iniValueText) strictly. Each returns nothing on success, else what was
/// expected ("an integer", "a number", "a boolean (true/false)", ...). Numbers must be finite; integers must
/// fit their type and carry no fraction.
std::optional<std::string> parseIniValue(const std::string& text, int& out);
std::optional<std::string> parseIniValue(const std::string& text, unsigned& out);
std::optional<std::string> parseIniValue(const std::string& text, long& out);
std::optional<std::string> parseIniValue(const std::string& text, unsigned long& out);
std::optional<std::string> parseIniValue(const std::string& text, double& out);
std::optional<std::string> parseIniValue(const std::string& text, float& out);
std::optional<std::string> parseIniValue(const std::string& text, bool& out);
std::optional<std::string> parseIniValue(const std::string& text, std::string& out);

/// The text an INI file holds for a value so that parseIniValue reads back the same value: numbers to 17
/// significant digits (doubles round-trip exactly), booleans as true / false, strings as they are.
std::string iniText(double v);
std::string iniText(int v);
std::string iniText(bool v);
std::string iniText(const std::string& v);

/// `value` from key `key` of `section` if the key exists (else unchanged). Works with any MRPT config
/// (CConfigFileBase: keyExists, read_string). Throws InputError("[section]", 0, key, "cannot parse '<text>' as
/// <what>") on a malformed value.
template <class Config, class T>
void readIniValue(const Config& cfg, const std::string& section, const std::string& key, T& value) {
  if (!cfg.keyExists(section, key)) return;
  const std::string text = iniValueText(cfg.read_string(section, key, "", false));
  T parsed{};
  if (const auto expected = parseIniValue(text, parsed))
    throw InputError("[" + section + "]", 0, key, "cannot parse '" + text + "' as " + *expected);
  value = parsed;
}

/// The same, returning the value (or `def` when the key is absent): a drop-in for cfg.read_int(...) etc.
template <class Config, class T>
T readIni(const Config& cfg, const std::string& section, const std::string& key, const T& def) {
  T value = def;
  readIniValue(cfg, section, key, value);
  return value;
}

}  // namespace gridtopo
