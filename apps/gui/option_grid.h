#pragma once
// A property grid over one session::OptionTable (the SLAM options, or the topology options): one property per key
// with its type (check box, number, word list), its help, range, unit and default in the description box, and the
// buttons Apply, Defaults and Save INI. What the grid edits goes back through the options struct's own loading and
// validation (the hooks), so the GUI accepts exactly what the command-line apps load.
#include <wx/wx.h>

#include <functional>
#include <map>
#include <string>

#include "gridtopo/session/option_table.h"

class wxPropertyGridManager;

namespace gridtopo::gui {

class OptionGrid : public wxPanel {
 public:
  struct Hooks {
    std::function<session::OptionTable()> table;               ///< the current values
    std::function<void(const session::OptionTable&)> apply;   ///< throws (InputError) on a bad value
    std::function<void()> defaults;                            ///< resets the options
    std::function<void()> save;                                ///< Save INI...
    std::function<void(const std::string&)> error;            ///< shows an error
    std::function<void()> applied;                              ///< after a successful Apply
  };
  OptionGrid(wxWindow* parent, Hooks hooks);

  /// Shows the current values (hooks.table()).
  void rebuild();
  /// Reads the edited values into a table and applies it; false (after hooks.error) when the options refuse it.
  bool applyEdits();
  /// Selects `section`'s `key` and shows its description.
  void select(const std::string& section, const std::string& key);

 private:
  static wxString propertyName(const session::OptionEntry& e) { return e.section + "_" + e.key; }
  Hooks hooks_;
  wxPropertyGridManager* grid_ = nullptr;
  std::map<std::string, std::string> shown_;  ///< each property's text as rebuild() showed it
};

}  // namespace gridtopo::gui
