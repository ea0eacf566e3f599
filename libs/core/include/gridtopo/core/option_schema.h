#pragma once
// One typed key table per options struct: for each INI key its name, the member it sets, its type, the values it
// accepts (a range of numbers or a set of words), its unit and one line of help; the default is the struct's own
// (a default-constructed struct). Everything else is derived from the table, so no key is written twice:
//   load()      MRPT loadFromConfigFile: strict parsing (ini_value.h), then validate();
//   save()      MRPT saveToConfigFile: every key, in table order, loadable to the same values (17 digits);
//   dump()      MRPT dumpToTextStream: one aligned "key = value" line per key;
//   validate()  every key in its range, then the rules between keys: InputError(file, 0, "[section] key", msg);
//   loadRun()   a RUN.ini's run section ([slam_run], ...) from its IniFile: an empty value leaves the key as it is,
//               the line of every key is recorded (KeyLines), errors name file, line, "[section] key";
//   keys()      the strict RUN.ini checks (IniFile::requireKnownKeys);
//   describe()  what a help text (optionsHelp) and the GUI's property grid show of each key.
// A struct's table sits next to the struct, e.g. `const OptionSchema<SlamOptions>& slamOptionSchema()`.
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/config/CLoadableOptions.h>

#include <algorithm>
#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"
#include "gridtopo/core/ini_value.h"

namespace gridtopo {

/// The numbers a key accepts: an interval whose ends may be open, closed or absent.
struct OptionRange {
  std::optional<double> lo, hi;
  bool lo_open = false, hi_open = false;

  static OptionRange any() { return {}; }
  static OptionRange atLeast(double v) { return {v, std::nullopt, false, false}; }      ///< [v, inf)
  static OptionRange above(double v) { return {v, std::nullopt, true, false}; }        ///< (v, inf)
  static OptionRange below(double v) { return {std::nullopt, v, false, true}; }        ///< (-inf, v)
  static OptionRange closed(double a, double b) { return {a, b, false, false}; }       ///< [a, b]
  static OptionRange leftOpen(double a, double b) { return {a, b, true, false}; }      ///< (a, b]
  static OptionRange rightOpen(double a, double b) { return {a, b, false, true}; }     ///< [a, b)

  bool contains(double v) const;
  /// "[0, 1]", "(0, 10]", ">= 0", "> 0", "< 0"; "" when any number goes.
  std::string text() const;
};

enum class OptionType { Bool, Int, Real, Text, Word };
/// "bool", "int", "real", "text", "word".
const char* toString(OptionType type);

/// One key as help texts and property grids show it.
struct OptionDescription {
  std::string key;
  OptionType type = OptionType::Text;
  std::string value, default_value;  ///< INI texts (what save() writes)
  std::string default_shown;         ///< the default as people read it: reals in their shortest text ("0.85")
  std::string range;                 ///< OptionRange::text(); "" = any
  std::vector<std::string> words;    ///< Word keys: the accepted words
  std::string unit, help;
};

/// One INI section and its keys (a struct whose options span several sections describes each).
struct OptionSection {
  std::string section;
  std::vector<OptionDescription> keys;
};

/// The shortest decimal text that reads back to `v` exactly ("0.15", not "0.14999999999999999"), for messages and
/// help; save() writes 17 digits.
std::string shortestText(double v);
/// The same at float precision (0.85f gives "0.85", not "0.85000002384185791").
std::string shortestText(float v);

/// The INI file an MRPT config reads (CConfigFile::getAssociatedFile), "<ini>" for a config in memory.
std::string iniFileName(const mrpt::config::CConfigFileBase& config);

/// An options help text: "[section]", then one line per key: key = default, type, range and unit, help.
std::string optionsHelp(const std::string& section, const std::vector<OptionDescription>& keys);

/// Where the keys of a run section stand in its RUN.ini (OptionSchema::loadRun), for the checks that come after the
/// loading (a missing value, a file that does not exist): the line of the section and of every key it holds.
struct KeyLines {
  std::size_t section = 0;                  ///< the line of "[section]"; 0 when the file has none
  std::map<std::string, std::size_t> keys;  ///< the line of each key the section holds (with an empty value too)

  /// The key's line, else the section's (where the key belongs), else 0.
  std::size_t of(const std::string& key) const;
  /// The key stands in the file (its value, unless empty, is the file's).
  bool has(const std::string& key) const { return keys.count(key) > 0; }
  /// A flag replaced the key's value: it is no longer the file's.
  void forget(const std::string& key) { keys.erase(key); }
  /// A flag's value, when given, replaces `value`, the key's value from the file (forget).
  template <class T>
  void overrideWith(const std::optional<T>& flag, T& value, const std::string& key) {
    if (!flag) return;
    value = *flag;
    forget(key);
  }
};

/// How a key reaches its member: `s.*member`, or a nested member `(s.*outer).*inner`.
template <class S, class T>
using OptionField = std::function<T&(S&)>;

template <class S, class T>
OptionField<S, T> field(T S::*member) {
  return [member](S& s) -> T& { return s.*member; };
}
template <class S, class M, class T>
OptionField<S, T> field(M S::*outer, T M::*inner) {
  return [outer, inner](S& s) -> T& { return (s.*outer).*inner; };
}

/// The INI text of a value: true / false, integers as they are, reals to 17 significant digits.
template <class T>
std::string optionText(const T& v) {
  if constexpr (std::is_same_v<T, bool>) return v ? "true" : "false";
  else if constexpr (std::is_same_v<T, std::string>) return v;
  else if constexpr (std::is_integral_v<T>) return std::to_string(v);
  else return iniText(static_cast<double>(v));
}

template <class S>
class OptionSchema {
 public:
  /// `title`: the struct's name in dump() ("gridtopo::slam::SlamOptions").
  explicit OptionSchema(std::string title) : title_(std::move(title)) {}

  /// A bool, integer, real or text key whose value lies in `range` (numbers only; any() for the others).
  template <class T>
  OptionSchema& add(const std::string& key, OptionField<S, T> member, OptionRange range, const std::string& unit,
                    const std::string& help) {
    static_assert(!std::is_enum_v<T>, "an enum key takes its words: addWords");
    Key k;
    k.info.key = key;
    k.info.type = std::is_same_v<T, bool>            ? OptionType::Bool
                  : std::is_same_v<T, std::string>   ? OptionType::Text
                  : std::is_integral_v<T>            ? OptionType::Int
                                                     : OptionType::Real;
    k.info.range = range.text();
    k.info.unit = unit;
    k.info.help = help;
    k.text = [member](const S& s) { return optionText(member(const_cast<S&>(s))); };
    k.shown = [member](const S& s) {
      const T& v = member(const_cast<S&>(s));
      if constexpr (std::is_floating_point_v<T>) return shortestText(v);
      else return optionText(v);
    };
    k.parse = [member](S& s, const std::string& text) -> std::optional<std::string> {
      T parsed{};
      if (const auto expected = parseIniValue(text, parsed)) return "cannot parse '" + text + "' as " + *expected;
      member(s) = parsed;
      return std::nullopt;
    };
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
      k.check = [member, range](const S& s) -> std::optional<std::string> {
        const double v = static_cast<double>(member(const_cast<S&>(s)));
        if (range.contains(v)) return std::nullopt;
        return "must be " + mustBe(range) + ", got " + shortestText(v);
      };
    }
    keys_.push_back(std::move(k));
    return *this;
  }
  template <class T>
  OptionSchema& add(const std::string& key, T S::*member, OptionRange range, const std::string& unit,
                    const std::string& help) {
    return add<T>(key, field(member), range, unit, help);
  }

  /// A key whose value is one of a few words, each standing for a value of the member (an enum, or the word itself).
  template <class T>
  OptionSchema& addWords(const std::string& key, OptionField<S, T> member,
                         std::vector<std::pair<std::string, T>> words, const std::string& help) {
    Key k;
    k.info.key = key;
    k.info.type = OptionType::Word;
    for (const auto& w : words) k.info.words.push_back(w.first);
    k.info.help = help;
    k.text = [member, words](const S& s) {
      for (const auto& [word, value] : words)
        if (value == member(const_cast<S&>(s))) return word;
      return std::string("?");
    };
    k.shown = k.text;
    const std::string expected = "must be " + wordList(k.info.words);
    k.parse = [member, words, expected](S& s, const std::string& text) -> std::optional<std::string> {
      for (const auto& [word, value] : words)
        if (word == text) {
          member(s) = value;
          return std::nullopt;
        }
      return expected;
    };
    k.check = [k_text = k.text, expected](const S& s) -> std::optional<std::string> {
      if (k_text(s) == "?") return expected;
      return std::nullopt;
    };
    keys_.push_back(std::move(k));
    return *this;
  }
  template <class T>
  OptionSchema& addWords(const std::string& key, T S::*member, std::vector<std::pair<std::string, T>> words,
                         const std::string& help) {
    return addWords<T>(key, field(member), std::move(words), help);
  }

  /// A key whose INI text is a comma-separated list of numbers, each in `range` ("10, 15"; empty = no number).
  OptionSchema& addRealList(const std::string& key, OptionField<S, std::vector<double>> member, OptionRange range,
                            const std::string& unit, const std::string& help) {
    Key k;
    k.info.key = key;
    k.info.type = OptionType::Text;
    k.info.range = range.text();
    k.info.unit = unit;
    k.info.help = "comma-separated: " + help;
    k.text = [member](const S& s) { return listText(member(const_cast<S&>(s)), false); };
    k.shown = [member](const S& s) { return listText(member(const_cast<S&>(s)), true); };
    k.parse = [member, range](S& s, const std::string& text) -> std::optional<std::string> {
      std::vector<double> values;
      std::stringstream in(text);
      for (std::string item; std::getline(in, item, ',');) {
        const auto first = item.find_first_not_of(" \t");
        if (first == std::string::npos) continue;
        item = item.substr(first, item.find_last_not_of(" \t") - first + 1);
        double v = 0;
        if (parseIniValue(item, v) || !range.contains(v))
          return "must be a comma-separated list of numbers " + mustBe(range) + ", got '" + item + "'";
        values.push_back(v);
      }
      member(s) = std::move(values);
      return std::nullopt;
    };
    k.check = [member, range](const S& s) -> std::optional<std::string> {
      for (double v : member(const_cast<S&>(s)))
        if (!range.contains(v)) return "must hold numbers " + mustBe(range) + ", got " + shortestText(v);
      return std::nullopt;
    };
    keys_.push_back(std::move(k));
    return *this;
  }
  OptionSchema& addRealList(const std::string& key, std::vector<double> S::*member, OptionRange range,
                            const std::string& unit, const std::string& help) {
    return addRealList(key, field(member), range, unit, help);
  }

  /// Every key and rule of the table of a member struct, in its order (a section that holds the keys of a nested
  /// options struct and its own, e.g. [training]: BoostOptions' keys, then TrainingOptions').
  template <class M>
  OptionSchema& addAll(const OptionSchema<M>& inner, OptionField<S, M> member) {
    auto of = [member](const S& s) -> M& { return member(const_cast<S&>(s)); };
    for (const auto& k : inner.keys_) {
      Key w;
      w.info = k.info;
      w.text = [of, f = k.text](const S& s) { return f(of(s)); };
      w.shown = [of, f = k.shown](const S& s) { return f(of(s)); };
      w.parse = [of, f = k.parse](S& s, const std::string& text) { return f(of(s), text); };
      if (k.check) w.check = [of, f = k.check](const S& s) { return f(of(s)); };
      keys_.push_back(std::move(w));
    }
    for (const auto& [key, check] : inner.rules_) rules_.push_back({key, [of, f = check](const S& s) { return f(of(s)); }});
    return *this;
  }
  template <class M>
  OptionSchema& addAll(const OptionSchema<M>& inner, M S::*member) {
    return addAll<M>(inner, field(member));
  }

  /// A rule between keys, checked after every key's range: the message when `s` breaks it, reported on `key`.
  OptionSchema& rule(const std::string& key, std::function<std::optional<std::string>(const S&)> check) {
    rules_.push_back({key, std::move(check)});
    return *this;
  }

  /// Reads every key of `section` that `source` holds (others keep their values), then validate(). Throws
  /// InputError(file, 0, "[section] key", ...) for a value that does not parse or lies out of range.
  void load(S& s, const mrpt::config::CConfigFileBase& source, const std::string& section) const {
    const std::string file = iniFileName(source);
    for (const Key& k : keys_) {
      if (!source.keyExists(section, k.info.key)) continue;
      const std::string text = iniValueText(source.read_string(section, k.info.key, "", false));
      if (const auto error = k.parse(s, text)) throw InputError(file, 0, "[" + section + "] " + k.info.key, *error);
    }
    validate(s, file, section);
  }

  /// Reads the run section `section` of a RUN.ini: every key the file holds with a value (an empty value leaves the
  /// key as it is), the lines of the section and its keys into `lines`, then validate(). Throws
  /// InputError(file, line, "[section] key", ...) for a value that does not parse or lies out of range.
  void loadRun(S& s, KeyLines& lines, const IniFile& ini, const std::string& section) const {
    lines.section = ini.line(section);
    for (const Key& k : keys_) {
      if (!ini.hasKey(section, k.info.key)) continue;
      const std::size_t line = ini.line(section, k.info.key);
      lines.keys[k.info.key] = line;
      const std::string text = ini.value(section, k.info.key).value_or("");
      if (text.empty()) continue;
      if (const auto error = k.parse(s, text))
        throw InputError(ini.name(), line, "[" + section + "] " + k.info.key, *error);
    }
    try {
      validate(s, ini.name(), section);
    } catch (const InputError& e) {
      throw ini.withLine(e);
    }
  }

  void save(const S& s, mrpt::config::CConfigFileBase& target, const std::string& section) const {
    for (const Key& k : keys_) target.write(section, k.info.key, k.text(s));
  }

  /// save() of one section as INI text: "[section]" and one "key = value" line per key.
  std::string ini(const S& s, const std::string& section) const {
    mrpt::config::CConfigFileMemory mem;
    save(s, mem, section);
    return mem.getContent();
  }

  void dump(const S& s, std::ostream& out) const {
    out << "----------- [" << title_ << "] ------------\n";
    std::size_t width = 0;
    for (const Key& k : keys_) width = std::max(width, k.info.key.size());
    for (const Key& k : keys_) out << k.info.key << std::string(width - k.info.key.size(), ' ') << " = " << k.text(s) << "\n";
  }

  void validate(const S& s, const std::string& file, const std::string& section) const {
    for (const Key& k : keys_)
      if (k.check)
        if (const auto error = k.check(s)) throw InputError(file, 0, "[" + section + "] " + k.info.key, *error);
    for (const auto& [key, check] : rules_)
      if (const auto error = check(s)) throw InputError(file, 0, "[" + section + "] " + key, *error);
  }

  std::vector<std::string> keys() const {
    std::vector<std::string> out;
    for (const Key& k : keys_) out.push_back(k.info.key);
    return out;
  }

  /// Every key with the value it has in `s` and in a default-constructed struct.
  std::vector<OptionDescription> describe(const S& s) const {
    const S defaults{};
    std::vector<OptionDescription> out;
    for (const Key& k : keys_) {
      OptionDescription d = k.info;
      d.value = k.text(s);
      d.default_value = k.text(defaults);
      d.default_shown = k.shown(defaults);
      out.push_back(std::move(d));
    }
    return out;
  }

  /// optionsHelp of the defaults.
  std::string help(const std::string& section) const { return optionsHelp(section, describe(S{})); }

  const std::string& title() const { return title_; }

 private:
  template <class>
  friend class OptionSchema;

  struct Key {
    OptionDescription info;
    std::function<std::string(const S&)> text;
    std::function<std::string(const S&)> shown;  ///< text for people (OptionDescription::default_shown)
    std::function<std::optional<std::string>(S&, const std::string&)> parse;  ///< the error, if any
    std::function<std::optional<std::string>(const S&)> check;                ///< empty: any value goes
  };

  static std::string mustBe(const OptionRange& r) {
    const std::string t = r.text();
    return t.empty() || t[0] == '[' || t[0] == '(' ? "in " + t : t;
  }
  static std::string listText(const std::vector<double>& values, bool shortest) {
    std::string s;
    for (double v : values) s += (s.empty() ? "" : ", ") + (shortest ? shortestText(v) : iniText(v));
    return s;
  }
  static std::string wordList(const std::vector<std::string>& words) {
    std::string s;
    for (std::size_t i = 0; i < words.size(); ++i)
      s += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
    return s;
  }

  std::string title_;
  std::vector<Key> keys_;
  std::vector<std::pair<std::string, std::function<std::optional<std::string>(const S&)>>> rules_;
};

/// MRPT's CLoadableOptions of a struct with a key table, every method through the table:
///   struct ScanSimulationOptions : TableOptions<ScanSimulationOptions, scanSimulationOptionSchema> {
///     static constexpr const char* kSection = "scan_simulation";  // validate()'s default section
///     ... members with their defaults ...
///   };
/// (the table's function declared before the struct, for the struct's own name).
template <class S, const OptionSchema<S>& (*table)()>
struct TableOptions : mrpt::config::CLoadableOptions {
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) override {
    table().load(static_cast<S&>(*this), source, section);
  }
  void saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const override {
    table().save(static_cast<const S&>(*this), target, section);
  }
  void dumpToTextStream(std::ostream& out) const override { table().dump(static_cast<const S&>(*this), out); }
  /// Every key in its range and the rules between keys: InputError(file, 0, "[section] key", ...).
  void validate(const std::string& file = "<options>", const std::string& section = S::kSection) const {
    table().validate(static_cast<const S&>(*this), file, section);
  }
};

}  // namespace gridtopo
