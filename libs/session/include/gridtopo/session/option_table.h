#pragma once
// Every key of a CLoadableOptions struct as a flat table (section, key, value, type, help) for a property
// grid: values come from the struct's own saveToConfigFile(), help from the comments of a documented INI
// (config-ini/*.ini, "key = value  # help"), and edits go back through the struct's loadFromConfigFile() and
// validation, so the GUI edits exactly what the command-line app loads.
#include <mrpt/config/CLoadableOptions.h>

#include <functional>
#include <string>
#include <vector>

namespace gridtopo::session {

struct OptionEntry {
  std::string section, key, value, default_value, help;
  enum class Type { Bool, Int, Double, String } type = Type::String;
};

class OptionTable {
 public:
  /// Builds the table from `options` (current values) and `defaults` (a default-constructed struct), both
  /// saved with saveToConfigFile(cfg, section).
  static OptionTable fromOptions(const mrpt::config::CLoadableOptions& options,
                                 const mrpt::config::CLoadableOptions& defaults,
                                 const std::string& section);
  /// Adds help text from a documented INI file ("key = value  # help", comment lines above a key also count).
  /// Missing file: no help, no error.
  void addHelpFromIni(const std::string& path);

  const std::vector<OptionEntry>& entries() const { return entries_; }
  const OptionEntry* find(const std::string& section, const std::string& key) const;
  /// Sets a value (as text). Returns false if the key does not exist.
  bool set(const std::string& section, const std::string& key, const std::string& value);
  /// INI text of the whole table (with the help as comments).
  std::string toIni() const;
  /// Loads the table into `options` through its loadFromConfigFile(cfg, section); throws what the struct
  /// throws (gridtopo::InputError naming the key) on bad values.
  void applyTo(mrpt::config::CLoadableOptions& options, const std::string& section) const;

 private:
  std::vector<OptionEntry> entries_;
};

}  // namespace gridtopo::session
