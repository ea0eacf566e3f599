#pragma once
// The main window: menus, toolbar, map canvas, plot panel, SLAM and topology option grids, inspector and status bar. Every
// action forwards to session::Session; the window only renders its state.
#include <wx/wx.h>

#include <atomic>
#include <functional>
#include <future>
#include <string>
#include <vector>

#include "gridtopo/session/recent_files.h"
#include "gridtopo/session/session.h"
#include "map_canvas.h"
#include "option_grid.h"
#include "plot_panel.h"

class wxNotebook;
class wxSplitterWindow;

namespace gridtopo::gui {

class MainFrame : public wxFrame {
 public:
  MainFrame(const wxString& title, const wxSize& size);
  ~MainFrame() override;

  session::Session& session() { return s_; }
  MapCanvas* canvas() { return canvas_; }

  /// Opens a file with a dialog on error (the session is unchanged). `resolution` > 0 skips the prompt for
  /// plain images. Returns true on success.
  bool openFile(const std::string& path, double resolution = 0);
  void setView(session::ViewMode m);
  void startSlam();
  /// Starts labelling + topology of the current map in a background thread.
  void startTopology();
  bool topologyRunning() const { return topology_future_.valid(); }
  /// Turns the live topology of the SLAM run on (every `update_every` updates and when the run pauses or ends, with
  /// the topology grid's options) or off; an error dialog and false when it cannot (no place model).
  bool setLiveTopology(bool on, unsigned update_every);
  /// Grabs the whole window as it is on screen.
  bool screenshot(const std::string& path);
  std::string inspectorText() const;
  void refreshNow();
  /// Shows the session's SLAM and topology options in their grids.
  void rebuildOptionGrid();
  /// Sets the View menu's layer check marks from the canvas's layers (after changing them in code).
  void syncLayerMenu();
  void showOptionsTab();
  /// Opens the place model the project ships (session::Session::openDefaultModel) and shows which model is loaded.
  void openDefaultModel();

  /// Command-line test hooks: each step is polled until it returns true.
  std::vector<std::function<bool()>> script;
  bool quit_when_done = false;  ///< close the window when the script is done (--quit)
  int exit_code = 0;
  session::RunnerOptions runner_options = [] {
    session::RunnerOptions o;
    o.snapshot_interval = 0.1;  // the live view redraws at 10 Hz while the filter runs
    return o;
  }();

 private:
  void buildMenus();
  void buildPanels();
  void rebuildRecentMenu();
  bool applyOptionGrid();  ///< the SLAM grid's edits into the session (false: refused, error shown)
  void saveOptionsIni(const std::string& title, const std::string& name, const std::string& text);
  void onTimer(wxTimerEvent&);
  void updateStatus();
  void showError(const std::string& what, const std::string& msg);
  void onOpen(wxCommandEvent&);
  void onDropFiles(const wxArrayString& files);
  void showModel();  ///< the loaded model in the Topology menu and the status bar
  static std::string joinedDataDirs();

  session::Session s_;
  session::RecentFiles recent_;
  MapCanvas* canvas_ = nullptr;
  PlotPanel* plots_ = nullptr;
  wxSplitterWindow* right_split_ = nullptr;
  void showPlots(bool show);
  OptionGrid* slam_grid_ = nullptr;
  OptionGrid* topology_grid_ = nullptr;
  wxTextCtrl* inspector_ = nullptr;
  wxNotebook* notebook_ = nullptr;
  wxMenu* recent_menu_ = nullptr;
  wxMenuItem* model_item_ = nullptr;
  wxMenuBar* menubar_ = nullptr;
  wxTimer timer_;
  std::uint64_t drawn_version_ = 0;
  std::uint64_t live_drawn_sequence_ = 0;  ///< the live topology result last drawn
  int plot_tick_ = 0;
  bool failure_shown_ = false;
  std::string hover_;
  std::future<session::TopologyData> topology_future_;
  std::atomic<int> topology_progress_{0};
  std::string topology_stage_;
  friend class DropTarget;
};

}  // namespace gridtopo::gui
