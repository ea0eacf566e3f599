#include "option_grid.h"

#include <wx/propgrid/advprops.h>
#include <wx/propgrid/manager.h>
#include <wx/propgrid/propgrid.h>

namespace gridtopo::gui {

OptionGrid::OptionGrid(wxWindow* parent, Hooks hooks) : wxPanel(parent), hooks_(std::move(hooks)) {
  grid_ = new wxPropertyGridManager(this, wxID_ANY, wxDefaultPosition, wxDefaultSize,
                                    wxPG_SPLITTER_AUTO_CENTER | wxPG_DESCRIPTION);
  auto* apply = new wxButton(this, wxID_APPLY, "Apply");
  auto* defaults = new wxButton(this, wxID_ANY, "Defaults");
  auto* save = new wxButton(this, wxID_SAVEAS, "Save INI...");
  auto* bs = new wxBoxSizer(wxHORIZONTAL);
  bs->Add(apply, 0, wxALL, 2);
  bs->Add(defaults, 0, wxALL, 2);
  bs->Add(save, 0, wxALL, 2);
  auto* vs = new wxBoxSizer(wxVERTICAL);
  vs->Add(grid_, 1, wxEXPAND);
  vs->Add(bs, 0);
  SetSizer(vs);
  grid_->Bind(wxEVT_PG_SELECTED, [this](wxPropertyGridEvent& e) {
    if (wxPGProperty* p = e.GetProperty()) grid_->SetDescription(p->GetLabel(), p->GetHelpString());
    e.Skip();
  });
  apply->Bind(wxEVT_BUTTON, [this](wxCommandEvent&) {
    if (applyEdits() && hooks_.applied) hooks_.applied();
  });
  defaults->Bind(wxEVT_BUTTON, [this](wxCommandEvent&) {
    hooks_.defaults();
    rebuild();
  });
  save->Bind(wxEVT_BUTTON, [this](wxCommandEvent&) {
    if (applyEdits()) hooks_.save();
  });
}

void OptionGrid::rebuild() {
  // One page, created once; a rebuild empties it (Clear() + AddPage() on the manager corrupts its state).
  if (grid_->GetPageCount() == 0) grid_->AddPage("options");
  auto* page = grid_->GetPage(0);
  page->Clear();
  shown_.clear();
  std::string section;
  const session::OptionTable table = hooks_.table();
  for (const auto& e : table.entries()) {
    if (e.section != section) page->Append(new wxPropertyCategory("[" + e.section + "]")), section = e.section;
    wxPGProperty* p = nullptr;
    const wxString name = propertyName(e);  // no '.': wxPropertyGrid reads it as a child path
    switch (e.type) {
      case session::OptionEntry::Type::Choice: {
        wxArrayString choices;
        for (const auto& w : e.words) choices.Add(w);
        p = new wxEnumProperty(e.key, name, choices);
        p->SetValueFromString(e.value);
        break;
      }
      case session::OptionEntry::Type::Bool:
        p = new wxBoolProperty(e.key, name, e.value == "true");
        p->SetAttribute(wxPG_BOOL_USE_CHECKBOX, true);
        break;
      case session::OptionEntry::Type::Int: p = new wxIntProperty(e.key, name, std::stoll(e.value)); break;
      case session::OptionEntry::Type::Double: p = new wxFloatProperty(e.key, name, std::stod(e.value)); break;
      case session::OptionEntry::Type::String: p = new wxStringProperty(e.key, name, e.value); break;
    }
    std::string help = e.help;
    if (!e.range.empty() || !e.unit.empty()) help += "  (" + e.range + (e.range.empty() || e.unit.empty() ? "" : " ") + e.unit + ")";
    help += "  [default " + e.default_value + "]";
    p->SetHelpString(help);
    page->Append(p);
    shown_[name.ToStdString()] = p->GetValueAsString().ToStdString();
  }
}

bool OptionGrid::applyEdits() {
  auto table = hooks_.table();
  for (const auto& e : table.entries()) {
    wxPGProperty* p = grid_->GetProperty(propertyName(e));
    if (!p) continue;
    std::string v = p->GetValueAsString().ToStdString();
    // A value the user left as shown keeps its exact text (the grid shows reals rounded).
    if (const auto it = shown_.find(propertyName(e).ToStdString()); it != shown_.end() && it->second == v) continue;
    if (e.type == session::OptionEntry::Type::Bool) v = p->GetValue().GetBool() ? "true" : "false";
    table.set(e.section, e.key, v);
  }
  try {
    hooks_.apply(table);
    return true;
  } catch (const std::exception& ex) {
    hooks_.error(ex.what());
    return false;
  }
}

void OptionGrid::select(const std::string& section, const std::string& key) {
  if (auto* p = grid_->GetProperty(section + "_" + key)) {
    grid_->SelectProperty(p, true);
    grid_->SetDescription(p->GetLabel(), p->GetHelpString());
    grid_->GetGrid()->EnsureVisible(p);
  }
}

}  // namespace gridtopo::gui
