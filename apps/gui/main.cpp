// gridtopo-gui: open a log or a map, watch the RBPF SLAM build the map, run the place labelling and topology,
// click into the result, and paint training labels. Command-line options double as test hooks
// (--run-steps, --run-topology, --click-cell, --screenshot, --quit) for the headless smoke test: gui_arguments.h.
#include <wx/wx.h>

#include <cstdlib>
#include <iostream>

#include "gridtopo/core/app_shell.h"
#include "gui_arguments.h"
#include "gui_script.h"
#include "main_frame.h"

using namespace gridtopo;

/// The wx application: the main frame, started with the parsed command line; its exit code is the frame's.
class GuiApp : public wxApp {
 public:
  GuiApp(gui::GuiArguments args, int& exit_code) : args_(std::move(args)), exit_code_(exit_code) {}
  bool OnInit() override {
    wxInitAllImageHandlers();
    auto* f = new gui::MainFrame("gridtopo-gui", wxSize(args_.width, args_.height));
    f->Bind(wxEVT_CLOSE_WINDOW, [f, this](wxCloseEvent& e) {
      exit_code_ = f->exit_code;
      e.Skip();
    });
    gui::startGui(f, args_);
    return true;
  }

 private:
  const gui::GuiArguments args_;
  int& exit_code_;
};

int main(int argc, char** argv) {
  // Bad usage exits 2, a bad value 1, --help 0, before any window opens (core/app_shell.h).
  gui::GuiArguments args;
  bool parsed = false;
  const int rc = runApp("gridtopo-gui", [&] {
    args = gui::parseGuiArguments(argc, argv);
    parsed = true;
    return 0;
  });
  if (!parsed) return rc;
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) {
    std::cerr << "gridtopo-gui: error: no display: set DISPLAY (or run it under xvfb-run -a)\n";
    return 1;
  }
  int exit_code = 0;
  wxApp::SetInstance(new GuiApp(std::move(args), exit_code));  // wxEntry runs it and deletes it
  // wx must not parse our options: give it the program name only.
  int wx_argc = 1;
  char* wx_argv[] = {argv[0], nullptr};
  const int wx_rc = wxEntry(wx_argc, wx_argv);
  return wx_rc != 0 ? wx_rc : exit_code;
}
