#pragma once
// Every key of an options struct as a flat table (section, key, value, default, type, range, unit, help, words) for
// a property grid. It is built from the struct's key tables (OptionSchema::describe: the same tables that load,
// save and validate the struct, so the grid shows every key with the help and range the command-line apps print
// with --help-options), and edits go back through the struct's loadFromConfigFile() and validation, so the GUI
// edits exactly what the command-line app loads.
#include <mrpt/config/CLoadableOptions.h>

#include <string>
#include <vector>

#include "gridtopo/core/option_schema.h"

namespace gridtopo::session {

struct OptionEntry {
  std::string section, key, value, default_value, help, range, unit;
  std::vector<std::string> words;  ///< Choice: the accepted words
  enum class Type { Bool, Int, Double, String, Choice } type = Type::String;
};

class OptionTable {
 public:
  /// The table of one or more option sections, each as its key table describes it (values and defaults included).
  static OptionTable fromSections(const std::vector<OptionSection>& sections);

  const std::vector<OptionEntry>& entries() const { return entries_; }
  const OptionEntry* find(const std::string& section, const std::string& key) const;
  /// Sets a value (as text). Returns false if the key does not exist.
  bool set(const std::string& section, const std::string& key, const std::string& value);
  /// INI text of the whole table (with the help as comments): loadable by the command-line apps.
  std::string toIni() const;
  /// Loads the table into `options` through its loadFromConfigFile(cfg, section); throws what the struct
  /// throws (gridtopo::InputError naming the section and the key) on bad values.
  void applyTo(mrpt::config::CLoadableOptions& options, const std::string& section) const;

 private:
  std::vector<OptionEntry> entries_;
};

}  // namespace gridtopo::session
