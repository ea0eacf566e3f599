#include "gridtopo/experiment/ini_document.h"

#include <fstream>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_value.h"

namespace gridtopo::experiment {
namespace {
std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}
}  // namespace

const IniEntry* IniSection::find(const std::string& key) const {
  for (const auto& e : entries)
    if (e.key == key) return &e;
  return nullptr;
}

const IniSection* IniDocument::find(const std::string& name) const {
  for (const auto& s : sections)
    if (s.name == name) return &s;
  return nullptr;
}

IniDocument parseIniDocument(const std::string& text, const std::string& path) {
  IniDocument doc;
  doc.path = path;
  std::istringstream in(text);
  std::string raw;
  std::size_t line = 0;
  while (std::getline(in, raw)) {
    ++line;
    const std::string s = trim(raw);
    if (s.empty() || s[0] == '#' || s[0] == ';') continue;
    if (s[0] == '[') {
      if (s.back() != ']' || s.size() < 3) throw InputError(path, line, s, "malformed section header");
      const std::string name = trim(s.substr(1, s.size() - 2));
      if (doc.find(name)) throw InputError(path, line, "[" + name + "]", "section given twice");
      doc.sections.push_back({name, line, {}});
      continue;
    }
    const auto eq = s.find('=');
    if (eq == std::string::npos) throw InputError(path, line, s, "expected 'key = value', '[section]' or a comment");
    const std::string key = trim(s.substr(0, eq));
    if (key.empty()) throw InputError(path, line, s, "empty key");
    if (doc.sections.empty()) throw InputError(path, line, key, "key before the first [section]");
    IniSection& sec = doc.sections.back();
    if (sec.find(key)) throw InputError(path, line, "[" + sec.name + "] " + key, "key given twice");
    sec.entries.push_back({key, iniValueText(s.substr(eq + 1)), line});
  }
  return doc;
}

IniDocument readIniDocument(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw InputError(path, "cannot open the INI file");
  std::ostringstream ss;
  ss << f.rdbuf();
  return parseIniDocument(ss.str(), path);
}

}  // namespace gridtopo::experiment
