#include "main_frame.h"

#include <wx/artprov.h>
#include <wx/dnd.h>
#include <wx/filedlg.h>
#include <wx/notebook.h>
#include <wx/numdlg.h>
#include <wx/splitter.h>
#include <wx/textdlg.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "gridtopo/core/data_dir.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"

namespace gridtopo::gui {

namespace fs = std::filesystem;
using session::ViewMode;

namespace {
// The source tree's datasets/, the last place the shipped data is looked for (gridtopo::dataDirs).
const char* const kBuildTimeDataDir = GRIDTOPO_BUILD_TIME_DATA_DIR;

enum Id {
  kSaveSlam = wxID_HIGHEST + 1, kSaveTopology, kSaveLabels, kExportView, kClearRecent,
  kSlamStart, kSlamPlay, kSlamPause, kSlamStep, kSlamRun, kSlamStop, kSlamUseMap, kSlamLoadIni, kSlamSaveIni,
  kSlamLive, kSlamLiveEvery,
  kTopoModelInfo, kTopoModel, kTopoRun, kStageClassified, kStageRelaxed, kStageCorrected,
  kLabelsStart, kLabelsOpen, kToolNone, kToolBrush, kToolFill, kCodeRoom, kCodeCorridor, kCodeDoorway, kCodeErase,
  kBrushBigger, kBrushSmaller, kUndo,
  kViewSlam, kViewTopology, kViewLabels, kFit,
  kLayerFirst,  // the View menu's layer toggles: kLayerFirst + their index in kLayerToggles
  kRecentFirst = wxID_HIGHEST + 200,
};
// The View menu's layer toggles, in menu order. The one table gives the items, their initial check marks (the
// defaults of session::Layers) and the flag each one switches, so a new layer is one line here.
struct LayerToggle {
  const char* label;
  const char* help;
  bool session::Layers::*flag;
};
const LayerToggle kLayerToggles[] = {
    {"Particles", "", &session::Layers::particles},
    {"Every particle's trajectory", "", &session::Layers::particle_paths},
    {"Best particle's path", "", &session::Layers::best_path},
    {"Odometry-only path", "", &session::Layers::odometry},
    {"Current scan", "", &session::Layers::scan},
    {"Loop closures", "the loop closure's edges as they are found (magenta; rejected ones dashed grey)",
     &session::Layers::closures},
    {"Optimised map (loop closure)",
     "once a loop is closed, the map at the pose graph's optimised poses; off: the best particle's map",
     &session::Layers::optimised_map},
    {"Opened trajectories", "", &session::Layers::trajectories},
    {"Label overlay", "", &session::Layers::labels},
    {"Region ids", "", &session::Layers::region_ids},
    {"Topological graph", "", &session::Layers::graph},
    {"Scale bar", "", &session::Layers::scale_bar},
};
constexpr int kLayerCount = static_cast<int>(std::size(kLayerToggles));
static_assert(kLayerFirst + kLayerCount < kRecentFirst, "the layer ids run into the recent-file ids");
std::string fmtTime(double s) {
  if (!(s >= 0)) return "-";
  char b[32];
  const int m = static_cast<int>(s / 60);
  std::snprintf(b, sizeof b, "%d:%04.1f", m, s - 60 * m);
  return b;
}
}  // namespace

class DropTarget : public wxFileDropTarget {
 public:
  explicit DropTarget(MainFrame* f) : f_(f) {}
  bool OnDropFiles(wxCoord, wxCoord, const wxArrayString& files) override {
    f_->onDropFiles(files);
    return true;
  }

 private:
  MainFrame* f_;
};

MainFrame::MainFrame(const wxString& title, const wxSize& size)
    : wxFrame(nullptr, wxID_ANY, title, wxDefaultPosition, size), timer_(this) {
  recent_.load(session::RecentFiles::defaultFile());
  buildMenus();
  buildPanels();
  CreateStatusBar(5);
  const int widths[] = {230, 140, 170, 300, -1};
  SetStatusWidths(5, widths);
  SetDropTarget(new DropTarget(this));
  canvas_->SetDropTarget(new DropTarget(this));  // GTK delivers drops to the window under the pointer
  Bind(wxEVT_TIMER, &MainFrame::onTimer, this);
  timer_.Start(33);  // at most 30 redraws per second, only when something changed
}

MainFrame::~MainFrame() {
  timer_.Stop();
  if (topology_future_.valid()) topology_future_.wait();
  // The children (the canvas draws from s_) must go before the members: wxFrame's destructor would destroy
  // them after s_, and GTK can deliver a paint event to the canvas in between.
  canvas_->on_hover = nullptr;
  canvas_->on_select = nullptr;
  DestroyChildren();
}

void MainFrame::buildMenus() {
  auto* file = new wxMenu;
  file->Append(wxID_OPEN, "&Open...\tCtrl+O", "Open a log, map, trajectory, relations, topology output, model or INI");
  recent_menu_ = new wxMenu;
  file->AppendSubMenu(recent_menu_, "Open &recent");
  file->AppendSeparator();
  file->Append(kSaveSlam, "Save SLAM &outputs...\tCtrl+S", "map (PNG, PGM+YAML, .gridmap.gz), .simplemap, trajectory");
  file->Append(kSaveTopology, "Save &topology outputs...", "the files gridtopo-topology writes");
  file->Append(kSaveLabels, "Save &labels as...", "labelled image in the training code 77/115/179/0");
  file->Append(kExportView, "&Export view to PNG...\tCtrl+E");
  file->AppendSeparator();
  file->Append(wxID_EXIT, "&Quit\tCtrl+Q");

  auto* slam = new wxMenu;
  slam->Append(kSlamStart, "&New run on the open log\tCtrl+N");
  slam->Append(kSlamPlay, "&Play\tF5");
  slam->Append(kSlamPause, "P&ause\tF6");
  slam->Append(kSlamStep, "Single &step\tF7");
  slam->Append(kSlamRun, "&Run to end\tF8");
  slam->Append(kSlamStop, "S&top\tF9");
  slam->AppendSeparator();
  slam->AppendCheckItem(kSlamLive, "Live &topology",
                        "recompute the labels and the graph of the best map while the SLAM runs (SLAM view)");
  slam->Append(kSlamLiveEvery, "Live topology &every...", "every how many SLAM updates ([topology_builder] update_every)");
  slam->AppendSeparator();
  slam->Append(kSlamUseMap, "Send &map to topology / labels", "use the SLAM map as the session map (the optimised one once a loop is closed)");
  slam->Append(kSlamLoadIni, "&Load INI...");
  slam->Append(kSlamSaveIni, "Save options as &INI...");

  auto* topo = new wxMenu;
  model_item_ = topo->Append(kTopoModelInfo, s_.modelDescription());  // which model is loaded (not a command)
  model_item_->Enable(false);
  topo->Append(kTopoModel, "Open place &model...");
  topo->Append(kTopoRun, "&Run labelling + topology\tCtrl+T");
  topo->AppendSeparator();
  topo->AppendRadioItem(kStageClassified, "Labels as &classified");
  topo->AppendRadioItem(kStageRelaxed, "Labels after &relaxation");
  topo->AppendRadioItem(kStageCorrected, "Labels after region &correction");
  topo->Check(kStageCorrected, true);

  auto* labels = new wxMenu;
  labels->Append(kLabelsStart, "&Start labelling the open map");
  labels->Append(kLabelsOpen, "&Open a labelled image...");
  labels->AppendSeparator();
  labels->AppendRadioItem(kToolNone, "&Pan / inspect");
  labels->AppendRadioItem(kToolBrush, "&Brush\tCtrl+B");
  labels->AppendRadioItem(kToolFill, "&Flood fill\tCtrl+Shift+F");
  labels->AppendSeparator();
  labels->AppendRadioItem(kCodeRoom, "&Room (77)\tCtrl+Shift+1");
  labels->AppendRadioItem(kCodeCorridor, "&Corridor (115)\tCtrl+Shift+2");
  labels->AppendRadioItem(kCodeDoorway, "&Doorway (179)\tCtrl+Shift+3");
  labels->AppendRadioItem(kCodeErase, "&Erase (0)\tCtrl+Shift+0");
  labels->Append(kBrushBigger, "Bigger brush\tCtrl+]");
  labels->Append(kBrushSmaller, "Smaller brush\tCtrl+[");
  labels->Append(kUndo, "&Undo\tCtrl+Z");

  auto* view = new wxMenu;
  view->AppendRadioItem(kViewSlam, "&SLAM view\tCtrl+1");
  view->AppendRadioItem(kViewTopology, "&Topology view\tCtrl+2");
  view->AppendRadioItem(kViewLabels, "&Label painter\tCtrl+3");
  view->Append(kFit, "&Fit to map\tHome");
  view->AppendSeparator();
  for (int i = 0; i < kLayerCount; ++i)
    view->AppendCheckItem(kLayerFirst + i, kLayerToggles[i].label, kLayerToggles[i].help);

  menubar_ = new wxMenuBar;
  menubar_->Append(file, "&File");
  menubar_->Append(slam, "&SLAM");
  menubar_->Append(topo, "&Topology");
  menubar_->Append(labels, "&Labels");
  menubar_->Append(view, "&View");
  SetMenuBar(menubar_);
  rebuildRecentMenu();

  // Handlers.
  Bind(wxEVT_MENU, &MainFrame::onOpen, this, wxID_OPEN);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) { Close(); }, wxID_EXIT);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    wxDirDialog d(this, "Output directory for the SLAM results");
    if (d.ShowModal() != wxID_OK) return;
    try {
      s_.saveSlamOutputs(d.GetPath().ToStdString());
      SetStatusText("saved to " + d.GetPath(), 4);
    } catch (const std::exception& e) {
      showError("Cannot save the SLAM outputs", e.what());
    }
  }, kSaveSlam);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    if (!s_.topology()) return showError("Nothing to save", "run or open a topology first");
    wxDirDialog d(this, "Output directory for the topology");
    if (d.ShowModal() != wxID_OK) return;
    try {
      session::saveTopologyOutputs(*s_.topology(), d.GetPath().ToStdString(), s_.topologyOptions());
    } catch (const std::exception& e) {
      showError("Cannot save the topology", e.what());
    }
  }, kSaveTopology);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    if (s_.canvas().empty()) return showError("Nothing to save", "start labelling a map first (Labels menu)");
    wxFileDialog d(this, "Save labels", "", "labels.png", "PNG (*.png)|*.png", wxFD_SAVE | wxFD_OVERWRITE_PROMPT);
    if (d.ShowModal() != wxID_OK) return;
    try {
      s_.canvas().save(d.GetPath().ToStdString());
    } catch (const std::exception& e) {
      showError("Cannot save the labels", e.what());
    }
  }, kSaveLabels);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    wxFileDialog d(this, "Export view", "", "view.png", "PNG (*.png)|*.png", wxFD_SAVE | wxFD_OVERWRITE_PROMPT);
    if (d.ShowModal() != wxID_OK) return;
    const cv::Mat img = canvas_->renderImage().clone();
    try {
      writeFileAtomically(d.GetPath().ToStdString(), [&](const std::string& p) {
        if (!cv::imwrite(p + ".png", img)) throw std::runtime_error("cannot write " + p);
        fs::rename(p + ".png", p);
      });
    } catch (const std::exception& e) {
      showError("Cannot export the view", e.what());
    }
  }, kExportView);
  Bind(wxEVT_MENU, [this](wxCommandEvent& e) {
    const std::size_t i = static_cast<std::size_t>(e.GetId() - kRecentFirst);
    if (i < recent_.paths().size()) openFile(recent_.paths()[i]);
  }, kRecentFirst, kRecentFirst + 20);

  Bind(wxEVT_MENU, [this](wxCommandEvent&) { startSlam(); }, kSlamStart);
  auto withRunner = [this](std::function<void(session::SlamRunner&)> f) {
    return [this, f](wxCommandEvent&) {
      if (!s_.runner()) {
        if (!s_.hasLog()) return showError("No log", "open a CARMEN log or an MRPT rawlog first");
        startSlam();
      }
      if (s_.runner()) f(*s_.runner());
    };
  };
  Bind(wxEVT_MENU, withRunner([](session::SlamRunner& r) { r.play(); }), kSlamPlay);
  Bind(wxEVT_MENU, withRunner([](session::SlamRunner& r) { r.pause(); }), kSlamPause);
  Bind(wxEVT_MENU, withRunner([](session::SlamRunner& r) { r.step(1); }), kSlamStep);
  Bind(wxEVT_MENU, withRunner([](session::SlamRunner& r) { r.play(); }), kSlamRun);
  Bind(wxEVT_MENU, withRunner([](session::SlamRunner& r) { r.stop(); }), kSlamStop);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    try {
      s_.useSlamMap();
      setView(ViewMode::Topology);
    } catch (const std::exception& e) {
      showError("No SLAM map", e.what());
    }
  }, kSlamUseMap);
  Bind(wxEVT_MENU, [this](wxCommandEvent& e) {
    setLiveTopology(e.IsChecked(), s_.liveTopologySchedule().update_every);
  }, kSlamLive);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    const long n = wxGetNumberFromUser("Recompute the live topology every N SLAM updates (0: only when the run pauses "
                                       "or ends).",
                                       "N", "Live topology", static_cast<long>(s_.liveTopologySchedule().update_every),
                                       0, 1000000, this);
    if (n >= 0) setLiveTopology(true, static_cast<unsigned>(n));
  }, kSlamLiveEvery);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    wxFileDialog d(this, "SLAM INI", "", "", "INI (*.ini)|*.ini|All files|*", wxFD_OPEN | wxFD_FILE_MUST_EXIST);
    if (d.ShowModal() == wxID_OK) openFile(d.GetPath().ToStdString());
  }, kSlamLoadIni);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    if (applyOptionGrid()) saveOptionsIni("Save SLAM options", "slam.ini", s_.slamOptionTable().toIni());
  }, kSlamSaveIni);

  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    wxFileDialog d(this, "Place model", "", "", "Models (*.yml;*.yaml;*.json)|*.yml;*.yaml;*.json|All files|*",
                   wxFD_OPEN | wxFD_FILE_MUST_EXIST);
    if (d.ShowModal() == wxID_OK) openFile(d.GetPath().ToStdString());
  }, kTopoModel);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) { startTopology(); }, kTopoRun);
  Bind(wxEVT_MENU, [this](wxCommandEvent& e) {
    canvas_->layers().stage = e.GetId() == kStageClassified ? session::LabelStage::Classified
                              : e.GetId() == kStageRelaxed  ? session::LabelStage::Relaxed
                                                            : session::LabelStage::Corrected;
    setView(ViewMode::Topology);
  }, kStageClassified, kStageCorrected);

  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    try {
      s_.startLabelling();
      canvas_->tool = PaintTool::Brush;
      menubar_->Check(kToolBrush, true);
      setView(ViewMode::Labels);
    } catch (const std::exception& e) {
      showError("Cannot start labelling", e.what());
    }
  }, kLabelsStart);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    wxFileDialog d(this, "Labelled image", "", "", "PNG (*.png)|*.png|All files|*", wxFD_OPEN | wxFD_FILE_MUST_EXIST);
    if (d.ShowModal() != wxID_OK) return;
    try {
      s_.openLabelImage(d.GetPath().ToStdString());
      setView(ViewMode::Labels);
    } catch (const std::exception& e) {
      showError("Cannot open the labels", e.what());
    }
  }, kLabelsOpen);
  Bind(wxEVT_MENU, [this](wxCommandEvent& e) {
    canvas_->tool = e.GetId() == kToolBrush ? PaintTool::Brush : e.GetId() == kToolFill ? PaintTool::Fill : PaintTool::None;
  }, kToolNone, kToolFill);
  Bind(wxEVT_MENU, [this](wxCommandEvent& e) {
    const unsigned char codes[] = {77, 115, 179, 0};
    canvas_->paint_code = codes[e.GetId() - kCodeRoom];
  }, kCodeRoom, kCodeErase);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) { canvas_->brush_radius = std::min(200, canvas_->brush_radius + 2); }, kBrushBigger);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) { canvas_->brush_radius = std::max(0, canvas_->brush_radius - 2); }, kBrushSmaller);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) {
    if (s_.canvas().undo()) s_.canvasChanged(), canvas_->Refresh(false);
  }, kUndo);

  Bind(wxEVT_MENU, [this](wxCommandEvent& e) {
    setView(e.GetId() == kViewSlam ? ViewMode::Slam : e.GetId() == kViewTopology ? ViewMode::Topology : ViewMode::Labels);
  }, kViewSlam, kViewLabels);
  Bind(wxEVT_MENU, [this](wxCommandEvent&) { canvas_->fit(); }, kFit);
  Bind(wxEVT_MENU, [this](wxCommandEvent& e) {
    canvas_->layers().*kLayerToggles[e.GetId() - kLayerFirst].flag = e.IsChecked();
    canvas_->Refresh(false);
  }, kLayerFirst, kLayerFirst + kLayerCount - 1);
}

void MainFrame::buildPanels() {
  auto* split = new wxSplitterWindow(this, wxID_ANY, wxDefaultPosition, wxDefaultSize, wxSP_LIVE_UPDATE);
  notebook_ = new wxNotebook(split, wxID_ANY);
  auto* right = new wxSplitterWindow(split, wxID_ANY, wxDefaultPosition, wxDefaultSize, wxSP_LIVE_UPDATE);
  right_split_ = right;
  canvas_ = new MapCanvas(right, s_);
  plots_ = new PlotPanel(right);
  right->SetSashGravity(1.0);
  right->Initialize(canvas_);  // the plots appear with the first SLAM run
  plots_->Hide();
  split->SplitVertically(notebook_, right, 300);
  split->SetMinimumPaneSize(120);

  // Inspector.
  inspector_ = new wxTextCtrl(notebook_, wxID_ANY, "Click a particle (SLAM view), a cell or a graph node (topology view).",
                              wxDefaultPosition, wxDefaultSize, wxTE_MULTILINE | wxTE_READONLY);
  inspector_->SetFont(wxFont(9, wxFONTFAMILY_TELETYPE, wxFONTSTYLE_NORMAL, wxFONTWEIGHT_NORMAL));
  inspector_->SetValue("Click a particle (SLAM view),\na cell or a graph node (topology view).\nHover: coordinates in the status bar.");
  inspector_->ShowPosition(0);
  // SLAM and topology options: the options' key tables, edited through the structs' own loading.
  auto error = [this](const std::string& what) {
    return [this, what](const std::string& msg) { showError(what, msg); };
  };
  slam_grid_ = new OptionGrid(
      notebook_, {[this] { return s_.slamOptionTable(); }, [this](const auto& t) { s_.setSlamOptions(t); },
                  [this] { s_.slamOptions() = slam::SlamOptions(); },
                  [this] {
                    wxCommandEvent e(wxEVT_MENU, kSlamSaveIni);
                    ProcessWindowEvent(e);
                  },
                  error("Invalid SLAM option"),
                  [this] { SetStatusText("options applied (used by the next run: SLAM > New run)", 4); }});
  topology_grid_ = new OptionGrid(
      notebook_, {[this] { return s_.topologyOptionTable(); }, [this](const auto& t) { s_.setTopologyOptions(t); },
                  [this] { s_.topologyOptions() = topology::TopologyOptions(); },
                  [this] { saveOptionsIni("Save topology options", "topology.ini", s_.topologyOptionTable().toIni()); },
                  error("Invalid topology option"),
                  [this] { SetStatusText("topology options applied (used by the next Topology > Run)", 4); }});
  notebook_->AddPage(inspector_, "Inspector", true);
  notebook_->AddPage(slam_grid_, "SLAM options");
  notebook_->AddPage(topology_grid_, "Topology options");
  rebuildOptionGrid();

  canvas_->on_hover = [this](const std::string& t) { SetStatusText(t, 4); };
  canvas_->on_select = [this]() {
    inspector_->SetValue(s_.selection().text);
    notebook_->SetSelection(0);
  };
  syncLayerMenu();
}

void MainFrame::syncLayerMenu() {
  const auto& l = canvas_->layers();
  for (int i = 0; i < kLayerCount; ++i) menubar_->Check(kLayerFirst + i, l.*kLayerToggles[i].flag);
}

void MainFrame::rebuildOptionGrid() {
  slam_grid_->rebuild();
  topology_grid_->rebuild();
}

bool MainFrame::applyOptionGrid() { return slam_grid_->applyEdits(); }

void MainFrame::saveOptionsIni(const std::string& title, const std::string& name, const std::string& text) {
  wxFileDialog d(this, title, "", name, "INI (*.ini)|*.ini", wxFD_SAVE | wxFD_OVERWRITE_PROMPT);
  if (d.ShowModal() != wxID_OK) return;
  try {
    writeTextFileAtomically(d.GetPath().ToStdString(), text);
  } catch (const std::exception& e) {
    showError("Cannot save the INI", e.what());
  }
}

void MainFrame::rebuildRecentMenu() {
  while (recent_menu_->GetMenuItemCount()) recent_menu_->Destroy(recent_menu_->FindItemByPosition(0));
  for (std::size_t i = 0; i < recent_.paths().size(); ++i)
    recent_menu_->Append(kRecentFirst + static_cast<int>(i), recent_.paths()[i]);
  if (recent_.paths().empty()) recent_menu_->Append(kClearRecent, "(none)")->Enable(false);
}

void MainFrame::showError(const std::string& what, const std::string& msg) {
  SetStatusText(what + ": " + msg, 4);
  if (!script.empty()) {  // scripted run: no modal dialog, report on stderr
    std::fprintf(stderr, "gridtopo-gui: %s: %s\n", what.c_str(), msg.c_str());
    exit_code = 1;
    return;
  }
  wxMessageBox(msg, what, wxOK | wxICON_ERROR, this);
}

bool MainFrame::openFile(const std::string& path, double resolution) {
  io::MapReadOptions mo;
  if (session::classifyFile(path) == session::FileKind::Map && session::mapNeedsResolution(path)) {
    if (resolution > 0) {
      mo.resolution = resolution;
    } else {
      wxTextEntryDialog d(this, "Resolution of " + fs::path(path).filename().string() + " (metres per pixel):",
                          "Map resolution", "0.05");
      if (d.ShowModal() != wxID_OK) return false;
      double r = 0;
      if (!d.GetValue().ToDouble(&r) || !(r > 0) || !std::isfinite(r)) {
        showError("Invalid resolution", "'" + d.GetValue().ToStdString() + "' is not a positive number");
        return false;
      }
      mo.resolution = r;
    }
  }
  wxBusyCursor busy;
  try {
    const auto kind = s_.open(path, mo);
    recent_.add(path);
    try {
      recent_.save(session::RecentFiles::defaultFile());
    } catch (const std::exception&) {
    }
    rebuildRecentMenu();
    SetStatusText(std::string("opened ") + session::toString(kind) + " " + path, 4);
    if (kind == session::FileKind::Log && !s_.logWarnings().empty()) {  // non-modal: the status bar says them
      std::string text = "opened " + path + ", reader warning(s):";
      for (const auto& w : s_.logWarnings()) text += " " + w + ";";
      SetStatusText(text, 4);
    }
    switch (kind) {
      case session::FileKind::Log:
        plots_->clear();
        setView(ViewMode::Slam);
        break;
      case session::FileKind::Map:
        setView(s_.runner() ? ViewMode::Topology : ViewMode::Slam);
        canvas_->fit();
        break;
      case session::FileKind::Topology: setView(ViewMode::Topology); break;
      case session::FileKind::SlamIni: rebuildOptionGrid(); break;
      case session::FileKind::Model: showModel(); break;
      default: break;
    }
    canvas_->Refresh(false);
    return true;
  } catch (const std::exception& e) {
    showError("Cannot open " + fs::path(path).filename().string(), e.what());
    return false;
  }
}

void MainFrame::openDefaultModel() {
  try {
    s_.openDefaultModel(kBuildTimeDataDir);
  } catch (const std::exception& e) {
    showError("Cannot open the shipped place model", e.what());
  }
  showModel();
}

void MainFrame::showModel() {
  model_item_->SetItemLabel(s_.modelDescription());
  SetStatusText(s_.modelDescription(), 4);
}

std::string MainFrame::joinedDataDirs() {
  std::string dirs;
  for (const auto& d : dataDirs(kBuildTimeDataDir)) dirs += (dirs.empty() ? "" : ", ") + d;
  return dirs;
}

void MainFrame::onOpen(wxCommandEvent&) {
  wxFileDialog d(this, "Open", "", "",
                 "All supported|*.clf;*.log;*.gz;*.rawlog;*.png;*.pgm;*.jpg;*.yaml;*.yml;*.gridmap;*.txt;*.relations;"
                 "*.json;*.graphml;*.ini|All files|*",
                 wxFD_OPEN | wxFD_FILE_MUST_EXIST | wxFD_MULTIPLE);
  if (d.ShowModal() != wxID_OK) return;
  wxArrayString paths;
  d.GetPaths(paths);
  onDropFiles(paths);
}

void MainFrame::onDropFiles(const wxArrayString& files) {
  for (const auto& f : files) openFile(f.ToStdString());
}

void MainFrame::showPlots(bool show) {
  if (show == right_split_->IsSplit()) return;
  if (show) {
    const int h = right_split_->GetClientSize().y;
    right_split_->SplitHorizontally(canvas_, plots_, std::max(100, h - 190));
  } else {
    right_split_->Unsplit(plots_);
  }
}

void MainFrame::setView(ViewMode m) {
  showPlots(m == ViewMode::Slam && s_.runner());
  canvas_->setMode(m);
  menubar_->Check(m == ViewMode::Slam ? kViewSlam : m == ViewMode::Topology ? kViewTopology : kViewLabels, true);
  canvas_->fit();
}

void MainFrame::startSlam() {
  if (!applyOptionGrid()) return;
  if (s_.liveTopologyOn() && !topology_grid_->applyEdits()) return;  // the live topology takes the topology options
  try {
    s_.startSlam(runner_options);
    failure_shown_ = false;
    plots_->clear();
    drawn_version_ = 0;
    live_drawn_sequence_ = 0;
    setView(ViewMode::Slam);
  } catch (const std::exception& e) {
    showError("Cannot start the SLAM", e.what());
  }
}

void MainFrame::startTopology() {
  if (topology_future_.valid()) return;
  if (s_.map().empty() && s_.runner()) {
    try {
      s_.useSlamMap();
    } catch (const std::exception&) {
    }
  }
  if (s_.map().empty()) return showError("No map", "open a map or run the SLAM first");
  if (!topology_grid_->applyEdits()) return;
  if (!s_.model())
    return showError("No place model", "open a model trained by gridtopo-train (Topology > Open place model); the "
                                       "shipped " + std::string(session::kDefaultModel) + " is in none of: " +
                                       joinedDataDirs());
  // The worker gets copies: the session is only touched again on the GUI thread when the result arrives.
  const session::MapLayer map = s_.map();
  const auto model = s_.model();
  const auto options = s_.topologyOptions();
  topology_progress_ = 0;
  topology_future_ = std::async(std::launch::async, [this, map, model, options] {
    return session::computeTopology(map, model, options, [this](const std::string&, std::size_t d, std::size_t n) {
      topology_progress_ = static_cast<int>(100 * d / std::max<std::size_t>(n, 1));
    });
  });
  SetStatusText("labelling places...", 4);
}

bool MainFrame::setLiveTopology(bool on, unsigned update_every) {
  if (on && !topology_grid_->applyEdits()) {
    menubar_->Check(kSlamLive, s_.liveTopologyOn());
    return false;
  }
  mapping::TopologyBuilderOptions schedule;
  schedule.update_every = update_every;
  try {
    s_.setLiveTopology(on, schedule);
  } catch (const std::exception& e) {
    menubar_->Check(kSlamLive, s_.liveTopologyOn());
    showError("No live topology", e.what());
    return false;
  }
  menubar_->Check(kSlamLive, on);
  live_drawn_sequence_ = 0;
  SetStatusText(on ? wxString::Format("live topology every %u updates and when the run pauses or ends", update_every)
                   : wxString("live topology off"),
                4);
  canvas_->Refresh(false);
  return true;
}

void MainFrame::showOptionsTab() {
  notebook_->SetSelection(1);
  slam_grid_->select("slam", "particles");
}

std::string MainFrame::inspectorText() const { return inspector_->GetValue().ToStdString(); }

void MainFrame::refreshNow() {
  canvas_->Refresh(false);
  canvas_->Update();
  if (const auto snap = s_.slamSnapshot()) plots_->update(*snap);
  updateStatus();
}

bool MainFrame::screenshot(const std::string& path) {
  Raise();
  refreshNow();
  wxYield();
  const wxRect r = GetScreenRect();
  wxScreenDC screen;
  wxBitmap bmp(r.width, r.height);
  {
    wxMemoryDC mem(bmp);
    mem.Blit(0, 0, r.width, r.height, &screen, r.x, r.y);
  }
  return bmp.SaveFile(path, wxBITMAP_TYPE_PNG);
}

void MainFrame::updateStatus() {
  const auto s = s_.slamSnapshot();
  if (!s) return;
  SetStatusText(wxString::Format("scan %zu / %zu (%zu updates)", s->scans_fed, s->scans_total, s->steps), 0);
  SetStatusText("t " + fmtTime(s->log_time) + " / " + fmtTime(s->log_duration), 1);
  SetStatusText(wxString::Format("%.0f scans/s, %s", s->scans_per_second, session::toString(s->state)), 2);
  std::string right = "ETA " + fmtTime(s->state == session::RunState::Running ? s->eta_seconds : -1);
  if (const auto err = s_.relationsError(*s))
    right += wxString::Format("  rel. err %.3f m / %.2f deg (%zu)", err->translational.mean, err->rotational.mean,
                              err->translational.count)
                 .ToStdString();
  SetStatusText(right, 3);
  if (s->state == session::RunState::Failed && !failure_shown_) {
    failure_shown_ = true;
    showError("SLAM failed", s->error);
  }
}

void MainFrame::onTimer(wxTimerEvent&) {
  if (topology_future_.valid()) {
    if (topology_future_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      try {
        s_.setTopology(topology_future_.get());
        SetStatusText(wxString::Format("topology: %zu regions, %zu edges, %.2f s", s_.topology()->topo.graph.nodes.size(),
                                       s_.topology()->topo.graph.edges.size(), s_.topology()->seconds),
                      4);
        setView(ViewMode::Topology);
      } catch (const std::exception& e) {
        topology_future_ = {};
        showError("Labelling failed", e.what());
      }
    } else {
      SetStatusText(wxString::Format("labelling places... %d%%", topology_progress_.load()), 4);
    }
  }
  if (const auto live = s_.liveTopologyResult(); live && live->sequence != live_drawn_sequence_) {
    live_drawn_sequence_ = live->sequence;
    if (canvas_->mode() == ViewMode::Slam) canvas_->Refresh(false);
    if (!topology_future_.valid()) SetStatusText(session::liveTopologyCaption(*live), 4);
  }
  if (const auto* r = s_.runner()) {
    const auto v = r->snapshotVersion();
    if (v != drawn_version_) {
      drawn_version_ = v;
      if (canvas_->mode() == ViewMode::Slam) canvas_->Refresh(false);
      if (++plot_tick_ % 10 == 0 || r->snapshot()->state != session::RunState::Running) {
        plots_->update(*r->snapshot());
        updateStatus();
      } else {
        const auto s = r->snapshot();
        SetStatusText(wxString::Format("scan %zu / %zu (%zu updates)", s->scans_fed, s->scans_total, s->steps), 0);
      }
    }
  }
  if (!script.empty()) {
    if (script.front()()) script.erase(script.begin());
    if (script.empty() && quit_when_done) Close(true);
  }
}

}  // namespace gridtopo::gui
