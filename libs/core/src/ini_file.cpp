#include "gridtopo/core/ini_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
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

// Edits (insert, delete, replace, swap of two neighbours) from a to b.
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& known, const std::string& open,
                       const std::string& close) {
  const std::string best = closestName(word, known);
  return best.empty() ? std::string() : "did you mean " + open + best + close + "? ";
}
}  // namespace

const std::vector<std::string>& gridtopoIniSections() {
  static const std::vector<std::string> sections = {
      "slam_run", "slam", "loop_closure", "topology_run", "topology", "relaxation", "correction", "map_run",
      "topology_builder", "relations_metric", "scan_simulation", "features", "training"};
  return sections;
}

std::string closestName(const std::string& word, const std::vector<std::string>& candidates) {
  // One edit for a name of up to 7 letters, two from 8 on.
  const std::size_t allowed = word.size() >= 8 ? 2 : 1;
  std::string best;
  std::size_t best_d = allowed + 1;
  for (const auto& c : candidates) {
    const std::size_t d = editDistance(word, c);
    if (d < best_d) best = c, best_d = d;
  }
  return best;
}

IniFile IniFile::read(const std::string& path) {
  errno = 0;
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, std::string("cannot read the INI file: ") + std::strerror(errno ? errno : ENOENT));
  std::ostringstream text;
  text << f.rdbuf();
  if (f.bad()) throw InputError(path, std::string("cannot read the INI file: ") + std::strerror(errno ? errno : EIO));
  const std::string s = text.str();
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f') || c == 0x7F) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", c);
      throw InputError(path, "not a text INI file (byte " + std::to_string(i) + " is " + hex + ")");
    }
  }
  return parse(s, path);
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
      throw InputError(name_, e.line, "[" + e.section + "]",
                       "unknown section (" + didYouMean(e.section, known, "[", "]") + "expected " + joined(known) + ")");
}

void IniFile::requireKnownKeys(const std::string& section, const std::vector<std::string>& known,
                               const std::string& where_listed) const {
  for (const auto& e : entries_)
    if (!e.key.empty() && e.section == section && std::find(known.begin(), known.end(), e.key) == known.end())
      throw InputError(name_, e.line, "[" + section + "] " + e.key,
                       "unknown key (" + didYouMean(e.key, known, "'", "'") +
                           (where_listed.empty() ? "expected " + joined(known) : where_listed) + ")");
}

void IniFile::requireSection(const std::string& section) const {
  if (!hasSection(section)) throw InputError(name_, 0, "[" + section + "]", "section not found");
}

void IniFile::requireOptionsFile(const std::vector<std::string>& read_here, const std::string& required) const {
  requireNoRepeats();
  std::vector<std::string> known = read_here;
  for (const auto& s : gridtopoIniSections())
    if (std::find(known.begin(), known.end(), s) == known.end()) known.push_back(s);
  for (const auto& e : entries_)
    if (e.key.empty() && std::find(known.begin(), known.end(), e.section) == known.end())
      throw InputError(name_, e.line, "[" + e.section + "]",
                       "unknown section (" + didYouMean(e.section, known, "[", "]") + "this app reads " +
                           joined(read_here) + ")");
  if (!required.empty()) requireSection(required);
}

}  // namespace gridtopo
