#pragma once
// An INI file read as written: sections and keys in file order, each with its line, so that an experiment's
// errors can name file, line, section and key (MRPT's CConfigFile keeps neither order nor lines). Lines are
// `[section]`, `key = value` (the value through core's iniValueText: trailing ` # comment` removed) or comments
// (first non-blank character '#' or ';'). A repeated section or key, a key outside a section or a line that is
// none of these is an InputError.
#include <cstddef>
#include <string>
#include <vector>

namespace gridtopo::experiment {

struct IniEntry {
  std::string key, value;
  std::size_t line = 0;
};

struct IniSection {
  std::string name;
  std::size_t line = 0;
  std::vector<IniEntry> entries;
  const IniEntry* find(const std::string& key) const;
};

struct IniDocument {
  std::string path;
  std::vector<IniSection> sections;
  const IniSection* find(const std::string& name) const;
};

IniDocument parseIniDocument(const std::string& text, const std::string& path);
/// Reads and parses `path`; a missing file is an InputError.
IniDocument readIniDocument(const std::string& path);

}  // namespace gridtopo::experiment
