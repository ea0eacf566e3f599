#include "option_grid.h"

#include <wx/propgrid/advprops.h>
#include <wx/propgrid/manager.h>
#include <wx/propgrid/propgrid.h>

namespace gridtopo::gui {
namespace {

// wxPropertyGridManager with its description box (wxPG_DESCRIPTION), without wx 3.2's warning at its first size
// event: there OnResize creates the box (RecreateControls) while the manager's width is still the "not sized yet"
// value -12345 that Init2 sets, and sizes the box's caption to that width - 6, which makes GTK print
// "Gtk-CRITICAL: gtk_widget_set_size_request: assertion 'width >= -1' failed" (once per manager: twice at start,
// for the SLAM and the topology options). This handler runs before OnResize (dynamic handlers come first): it gives
// the manager its real width and creates the box itself, then lets OnResize lay everything out as usual.
class DescribedGridManager : public wxPropertyGridManager {
 public:
  DescribedGridManager(wxWindow* parent, long style) {
    Bind(wxEVT_SIZE, &DescribedGridManager::onFirstSize, this);  // before Create, which sends the first size event
    Create(parent, wxID_ANY, wxDefaultPosition, wxDefaultSize, style | wxPG_DESCRIPTION);
  }

 private:
  static constexpr int kNotSized = -12345;  // wxPropertyGridManager::Init2's m_width until the first OnResize
  void onFirstSize(wxSizeEvent& e) {
    if (m_width == kNotSized) {
      m_width = GetClientSize().x;  // what the box is laid out with before RecalculatePositions sets it
      RecreateControls();           // as OnResize would (it skips it now that m_width is set)
    }
    e.Skip();  // OnResize
  }
};

}  // namespace

OptionGrid::OptionGrid(wxWindow* parent, Hooks hooks) : wxPanel(parent), hooks_(std::move(hooks)) {
  grid_ = new DescribedGridManager(this, wxPG_SPLITTER_AUTO_CENTER);
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
