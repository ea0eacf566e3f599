#pragma once
// The layout of an INI file: its sections and keys in file order, with their line numbers and value texts. MRPT's
// config classes read values but cannot say on which line a key sits, nor list what they did not expect; this
// does both, for the strict checks and the error messages of the apps' RUN.ini files.
// Syntax as in MRPT's INI files: "[section]", "key = value", comments after ';', '#' or "//" (whole lines, or after
// white space behind a value); MRPT's "@define" lines are skipped.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_value.h"

namespace gridtopo {

/// Every INI section that some gridtopo app reads (the option tables' sections and the RUN.ini run sections).
const std::vector<std::string>& gridtopoIniSections();

/// The closest of `candidates` to `word` (one edit: insert, delete, replace or swap two neighbours; two for a word of
/// 8 letters or more), else empty.
std::string closestName(const std::string& word, const std::vector<std::string>& candidates);

class IniFile {
 public:
  /// Reads `path`; InputError(path, "cannot read the INI file: <system's reason>") if it cannot be read, and
  /// InputError(path, "not a text INI file (byte N is 0xXX)") for a file with a NUL, DEL or another control byte than
  /// tab, CR, LF or form feed (an executable or an image given by mistake): refused before anything is parsed.
  static IniFile read(const std::string& path);
  /// Parses `text`; `name` stands for the file in error messages.
  static IniFile parse(const std::string& text, const std::string& name);

  const std::string& name() const { return name_; }
  bool hasSection(const std::string& section) const;
  bool hasKey(const std::string& section, const std::string& key) const;
  /// The sections in file order (each once).
  std::vector<std::string> sections() const;
  /// The keys of `section` in file order (each once).
  std::vector<std::string> keys(const std::string& section) const;
  /// The 1-based line of `[section]` (key empty) or of `key` in it; 0 when absent.
  std::size_t line(const std::string& section, const std::string& key = "") const;
  /// The line of `key` in `section`, else of the section's header (where the key belongs); 0 when neither is there.
  std::size_t lineOrSection(const std::string& section, const std::string& key) const;
  /// `e` with the line of the key its field names ("[section] key", as the options' loaders name it) when `e` names
  /// no line and the key is in this file; else `e` as it is.
  InputError withLine(const InputError& e) const;
  /// The value of `key` without its comment (iniValueText); nothing when absent. The last one wins, as in MRPT.
  std::optional<std::string> value(const std::string& section, const std::string& key) const;
  /// Parses the value of `key` into `out` (parseIniValue); false, `out` untouched, when the key is absent. Throws
  /// InputError(name, line, "[section] key", "cannot parse 'text' as ...") for a value of the wrong kind.
  template <class T>
  bool parseValue(const std::string& section, const std::string& key, T& out) const {
    const auto v = value(section, key);
    if (!v) return false;
    T parsed{};
    if (const auto expected = parseIniValue(*v, parsed))
      throw InputError(name_, line(section, key), "[" + section + "] " + key,
                       "cannot parse '" + *v + "' as " + *expected);
    out = parsed;
    return true;
  }

  /// Throws InputError(name, line, "[section]", "section given twice") or (name, line, "[section] key", "key given
  /// twice") for the first repeated section header or key (MRPT merges them; a strict file refuses them).
  void requireNoRepeats() const;
  /// Throws InputError(name, line, "[section]", "unknown section (did you mean [x]? expected ...)") for the first
  /// section that is not in `known` ("did you mean" for a name within two edits of a known one).
  void requireKnownSections(const std::vector<std::string>& known) const;
  /// Throws InputError(name, line, "[section] key", "unknown key (did you mean 'x'? expected ...)") for the first key
  /// of `section` that is not in `known`; `where_listed` (e.g. "see config-ini/slam.ini") replaces the list of a
  /// long table.
  void requireKnownKeys(const std::string& section, const std::vector<std::string>& known,
                        const std::string& where_listed = "") const;
  /// Throws InputError(name, 0, "[section]", "section not found") when the file has no `[section]`: the one message
  /// of every app whose options INI lacks the section it reads.
  void requireSection(const std::string& section) const;
  /// The checks of an options INI given with `-c`: no repeated key; every section one that this app reads
  /// (`read_here`) or another gridtopo app's (gridtopoIniSections(): one INI may serve several apps), else refused
  /// as unknown with a "did you mean"; `required` present.
  void requireOptionsFile(const std::vector<std::string>& read_here, const std::string& required) const;

 private:
  struct Entry {
    std::string section, key, value;  ///< key empty: the section's header line
    std::size_t line = 0;
  };
  std::string name_;
  std::vector<Entry> entries_;
};

}  // namespace gridtopo
