#include "gridtopo/core/ini_file.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_value.h"

namespace gridtopo {

namespace {
std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}

std::string joined(const std::vector<std::string>& words) {
  std::string s;
  for (const auto& w : words) s += (s.empty() ? "" : ", ") + w;
  return s;
}
}  // namespace

IniFile IniFile::read(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw InputError(path, "cannot read the INI file");
  std::ostringstream text;
  text << f.rdbuf();
  return parse(text.str(), path);
}

IniFile IniFile::parse(const std::string& text, const std::string& name) {
  IniFile ini;
  ini.name_ = name;
  std::istringstream in(text);
  std::string raw, section;
  std::size_t line = 0;
  while (std::getline(in, raw)) {
    ++line;
    const std::string s = trim(raw);
    if (s.empty() || s[0] == ';' || s[0] == '#' || s.rfind("//", 0) == 0 || s[0] == '@') continue;
    if (s[0] == '[') {
      const auto close = s.find(']');
      if (close == std::string::npos) throw InputError(name, line, s, "a section header without ']'");
      section = trim(s.substr(1, close - 1));
      ini.entries_.push_back({section, "", "", line});
      continue;
    }
    const auto eq = s.find('=');
    if (eq == std::string::npos) throw InputError(name, line, s, "expected 'key = value' or '[section]'");
    const std::string key = trim(s.substr(0, eq));
    if (key.empty()) throw InputError(name, line, "", "a value without a key");
    if (section.empty()) throw InputError(name, line, key, "a key before the first [section]");
    ini.entries_.push_back({section, key, iniValueText(s.substr(eq + 1)), line});
  }
  return ini;
}

bool IniFile::hasSection(const std::string& section) const { return line(section) > 0; }

bool IniFile::hasKey(const std::string& section, const std::string& key) const { return line(section, key) > 0; }

std::vector<std::string> IniFile::sections() const {
  std::vector<std::string> out;
  for (const auto& e : entries_)
    if (e.key.empty() && std::find(out.begin(), out.end(), e.section) == out.end()) out.push_back(e.section);
  return out;
}

std::vector<std::string> IniFile::keys(const std::string& section) const {
  std::vector<std::string> out;
  for (const auto& e : entries_)
    if (!e.key.empty() && e.section == section && std::find(out.begin(), out.end(), e.key) == out.end())
      out.push_back(e.key);
  return out;
}

std::size_t IniFile::line(const std::string& section, const std::string& key) const {
  for (const auto& e : entries_)
    if (e.section == section && e.key == key) return e.line;
  return 0;
}

std::size_t IniFile::lineOrSection(const std::string& section, const std::string& key) const {
  const std::size_t l = line(section, key);
  return l > 0 ? l : line(section);
}

InputError IniFile::withLine(const InputError& e) const {
  const std::string& field = e.field();
  const auto close = field.find("] ");
  if (e.line() > 0 || field.rfind("[", 0) != 0 || close == std::string::npos) return e;
  const std::size_t l = line(field.substr(1, close - 1), field.substr(close + 2));
  return l > 0 ? InputError(name_, l, field, e.message()) : e;
}

std::optional<std::string> IniFile::value(const std::string& section, const std::string& key) const {
  std::optional<std::string> v;
  for (const auto& e : entries_)
    if (!key.empty() && e.section == section && e.key == key) v = e.value;
  return v;
}

void IniFile::requireNoRepeats() const {
  for (std::size_t i = 0; i < entries_.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (entries_[j].section == entries_[i].section && entries_[j].key == entries_[i].key)
        throw entries_[i].key.empty()
            ? InputError(name_, entries_[i].line, "[" + entries_[i].section + "]", "section given twice")
            : InputError(name_, entries_[i].line, "[" + entries_[i].section + "] " + entries_[i].key,
                         "key given twice");
}

void IniFile::requireKnownSections(const std::vector<std::string>& known) const {
  for (const auto& e : entries_)
    if (e.key.empty() && std::find(known.begin(), known.end(), e.section) == known.end())
      throw InputError(name_, e.line, "[" + e.section + "]", "unknown section (expected " + joined(known) + ")");
}

void IniFile::requireKnownKeys(const std::string& section, const std::vector<std::string>& known,
                               const std::string& where_listed) const {
  for (const auto& e : entries_)
    if (!e.key.empty() && e.section == section && std::find(known.begin(), known.end(), e.key) == known.end())
      throw InputError(name_, e.line, "[" + section + "] " + e.key,
                       "unknown key (" + (where_listed.empty() ? "expected " + joined(known) : where_listed) + ")");
}

}  // namespace gridtopo
