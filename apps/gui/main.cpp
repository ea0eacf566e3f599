// gridtopo-gui: open a log or a map, watch the RBPF SLAM build the map, run the place labelling and topology,
// click into the result, and paint training labels. Command-line options double as test hooks
// (--run-steps, --run-topology, --click-cell, --screenshot, --quit) for the headless smoke test: gui_arguments.h.
#include <wx/wx.h>

#include "gridtopo/core/app_shell.h"
#include "gui_arguments.h"
#include "gui_script.h"
#include "main_frame.h"

using namespace gridtopo;

namespace {
gui::GuiArguments g_args;
int g_exit_code = 0;
}  // namespace

class GuiApp : public wxApp {
 public:
  bool OnInit() override {
    wxInitAllImageHandlers();
    auto* f = new gui::MainFrame("gridtopo-gui", wxSize(g_args.width, g_args.height));
    f->Bind(wxEVT_CLOSE_WINDOW, [f](wxCloseEvent& e) {
      g_exit_code = f->exit_code;
      e.Skip();
    });
    gui::startGui(f, g_args);
    return true;
  }
};

wxIMPLEMENT_APP_NO_MAIN(GuiApp);

int main(int argc, char** argv) {
  // Bad usage exits 2, a bad value 1, --help 0, before any window opens (core/app_shell.h).
  bool parsed = false;
  const int rc = runApp("gridtopo-gui", [&] {
    g_args = gui::parseGuiArguments(argc, argv);
    parsed = true;
    return 0;
  });
  if (!parsed) return rc;
  // wx must not parse our options: give it the program name only.
  int wx_argc = 1;
  char* wx_argv[] = {argv[0], nullptr};
  const int wx_rc = wxEntry(wx_argc, wx_argv);
  return wx_rc != 0 ? wx_rc : g_exit_code;
}
