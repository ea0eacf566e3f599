#include "gridtopo/session/option_table.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

namespace gridtopo::session {

namespace {
std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}
OptionEntry::Type guessType(const std::string& v) {
  if (v == "true" || v == "false") return OptionEntry::Type::Bool;
  if (v.empty()) return OptionEntry::Type::String;
  char* end = nullptr;
  std::strtoll(v.c_str(), &end, 10);
  if (*end == '\0' && v.find_first_of(".eE") == std::string::npos) return OptionEntry::Type::Int;
  std::strtod(v.c_str(), &end);
  if (*end == '\0') return OptionEntry::Type::Double;
  return OptionEntry::Type::String;
}
}  // namespace

OptionTable OptionTable::fromOptions(const mrpt::config::CLoadableOptions& options,
                                     const mrpt::config::CLoadableOptions& defaults, const std::string& section) {
  mrpt::config::CConfigFileMemory cur, def;
  options.saveToConfigFile(cur, section);
  defaults.saveToConfigFile(def, section);
  OptionTable t;
  std::vector<std::string> sections;
  cur.getAllSections(sections);
  for (const auto& sec : sections) {
    std::vector<std::string> keys;
    cur.getAllKeys(sec, keys);
    for (const auto& key : keys) {
      OptionEntry e;
      e.section = sec;
      e.key = key;
      e.value = cur.read_string(sec, key, "");
      e.default_value = def.read_string(sec, key, "");
      e.type = guessType(e.default_value);
      if (e.type == OptionEntry::Type::Int && guessType(e.value) == OptionEntry::Type::Double)
        e.type = OptionEntry::Type::Double;
      t.entries_.push_back(e);
    }
  }
  return t;
}

void OptionTable::addHelpFromIni(const std::string& path) {
  // Help of a key: the comment lines right above it (or, for keys listed under one comment, the help of the
  // previous key of the block), or an inline "# ..." after its value. Separator lines ("# ----- title") and blank
  // lines end a block.
  std::ifstream in(path);
  if (!in) return;
  std::string line, section, pending, block_help;
  while (std::getline(in, line)) {
    const std::string s = trim(line);
    if (s.empty()) {
      pending.clear(), block_help.clear();
      continue;
    }
    if (s[0] == '[') {
      section = trim(s.substr(1, s.find(']') - 1));
      pending.clear(), block_help.clear();
      continue;
    }
    if (s[0] == '#' || s[0] == ';') {
      const std::string c = trim(s.substr(1));
      if (c.find("----") != std::string::npos) {
        pending.clear(), block_help.clear();
      } else {
        pending += (pending.empty() ? "" : " ") + c;
      }
      continue;
    }
    const auto eq = s.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = trim(s.substr(0, eq));
    std::string help;
    const auto hash = s.find_first_of("#;", eq);
    if (hash != std::string::npos) help = trim(s.substr(hash + 1));
    if (help.empty()) help = pending.empty() ? block_help : pending;
    block_help = help;
    pending.clear();
    for (auto& e : entries_)
      if (e.key == key && (section.empty() || e.section == section) && e.help.empty()) e.help = help;
  }
}

const OptionEntry* OptionTable::find(const std::string& section, const std::string& key) const {
  for (const auto& e : entries_)
    if (e.section == section && e.key == key) return &e;
  return nullptr;
}

bool OptionTable::set(const std::string& section, const std::string& key, const std::string& value) {
  for (auto& e : entries_)
    if (e.section == section && e.key == key) {
      e.value = trim(value);
      return true;
    }
  return false;
}

std::string OptionTable::toIni() const {
  std::ostringstream o;
  o << "# written by gridtopo-gui\n";
  std::string section;
  for (const auto& e : entries_) {
    if (e.section != section) {
      section = e.section;
      o << "\n[" << section << "]\n";
    }
    // Help on its own comment line: MRPT's INI reader keeps inline comments as part of the value.
    if (!e.help.empty()) o << "# " << e.help << "\n";
    o << e.key << " = " << e.value << "\n";
  }
  return o.str();
}

void OptionTable::applyTo(mrpt::config::CLoadableOptions& options, const std::string& section) const {
  mrpt::config::CConfigFileMemory cfg;
  for (const auto& e : entries_) cfg.write(e.section, e.key, e.value);
  options.loadFromConfigFile(cfg, section);
}

}  // namespace gridtopo::session
