#include "gridtopo/session/option_table.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <sstream>

namespace gridtopo::session {

namespace {
std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}
OptionEntry::Type entryType(OptionType t) {
  switch (t) {
    case OptionType::Bool: return OptionEntry::Type::Bool;
    case OptionType::Int: return OptionEntry::Type::Int;
    case OptionType::Real: return OptionEntry::Type::Double;
    case OptionType::Word: return OptionEntry::Type::Choice;
    case OptionType::Text: break;
  }
  return OptionEntry::Type::String;
}
}  // namespace

OptionTable OptionTable::fromSections(const std::vector<OptionSection>& sections) {
  OptionTable t;
  for (const auto& s : sections)
    for (const auto& k : s.keys) {
      OptionEntry e;
      e.section = s.section;
      e.key = k.key;
      e.value = k.value;
      e.default_value = k.default_value;
      e.help = k.help;
      e.range = k.range;
      e.unit = k.unit;
      e.words = k.words;
      e.type = entryType(k.type);
      t.entries_.push_back(std::move(e));
    }
  return t;
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
