// gridtopo-gui: open a log or a map, watch the RBPF SLAM build the map, run the place labelling and topology,
// click into the result, and paint training labels. Command-line options double as test hooks
// (--run-steps, --run-topology, --click-cell, --screenshot, --quit) for the headless smoke test.
#include <tclap/CmdLine.h>
#include <wx/uiaction.h>
#include <wx/wx.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "gridtopo/core/error.h"
#include "main_frame.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {

struct Options {
  std::vector<std::string> files;
  std::string ini, model, topology_ini, screenshot, export_view, inspector_out, view, bench_out;
  double resolution = 0;
  long max_scans = 0, run_steps = -1, particles = 0, live_topology = -1;
  bool run_to_end = false, run_topology = false, quit = false, use_slam_map = false;
  int click_col = -1, click_row = -1;
  int width = 1280, height = 860;
  int bench_frames = 0;
  int tile_cols = 0, tile_rows = 0;
  bool particle_paths = false, click_particle = false, show_options = false;
  std::string labels, save_slam;
};
Options g_opt;
int g_exit_code = 0;

std::function<bool()> waitIdle(gui::MainFrame* f) {
  return [f] {
    auto* r = f->session().runner();
    if (!r) return true;
    return r->waitIdle(std::chrono::milliseconds(0));
  };
}

// Frame-rate benchmark: pans and zooms the view for n frames, each fully rendered and blitted (Update() paints
// synchronously), first with the whole map in view, then zoomed to 2 screen pixels per cell.
bool benchFrames(gui::MainFrame* f, int n, const std::string& out) {
  auto* c = f->canvas();
  const wxSize sz = c->GetClientSize();
  std::ostringstream o;
  for (int phase = 0; phase < 2; ++phase) {
    c->fit();
    c->auto_fit = false;
    if (phase == 1) {
      const double res = f->session().map().resolution;
      c->view().zoomAt(sz.x / 2.0, sz.y / 2.0, 2.0 / (res * c->view().ppm));
    }
    c->Refresh(false);
    c->Update();
    c->frames = 0;
    c->render_seconds = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) {
      if (i % 40 < 20) c->view().pan(phase ? 9 : 3, phase ? 5 : 2);
      else c->view().zoomAt(sz.x / 2.0, sz.y / 2.0, (i / 40) % 2 ? 1.0 / 1.02 : 1.02);
      c->Refresh(false);
      c->Update();
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    o << (phase ? "zoomed (2 px/cell)" : "whole map") << ": frames " << c->frames << " wall_s " << wall << " fps "
      << c->frames / wall << " render_ms_per_frame " << 1000.0 * c->render_seconds / std::max(1L, c->frames)
      << " canvas " << sz.x << "x" << sz.y << " map " << f->session().map().cols() << "x"
      << f->session().map().rows() << "\n";
  }
  std::cerr << o.str();
  if (!out.empty()) std::ofstream(out, std::ios::app) << o.str();
  return true;
}

}  // namespace

class GuiApp : public wxApp {
 public:
  bool OnInit() override {
    wxInitAllImageHandlers();
    frame_ = new gui::MainFrame("gridtopo-gui", wxSize(g_opt.width, g_opt.height));
    auto* f = frame_;
    const bool scripted = g_opt.run_steps >= 0 || g_opt.run_to_end || g_opt.run_topology || !g_opt.screenshot.empty() ||
                          g_opt.click_col >= 0 || g_opt.quit || g_opt.bench_frames > 0;
    if (scripted) f->script.push_back([] { return true; });  // errors go to stderr, not to modal dialogs
    f->quit_when_done = g_opt.quit;
    f->Bind(wxEVT_CLOSE_WINDOW, [f](wxCloseEvent& e) {
      g_exit_code = f->exit_code;
      e.Skip();
    });
    if (g_opt.max_scans > 0) f->runner_options.max_scans = static_cast<std::size_t>(g_opt.max_scans);
    f->Show();
    bool ok = true;
    if (!g_opt.ini.empty()) ok = f->openFile(g_opt.ini) && ok;
    if (!g_opt.topology_ini.empty()) {
      try {
        f->session().openTopologyIni(g_opt.topology_ini);
        f->rebuildOptionGrid();
      } catch (const std::exception& e) {
        std::cerr << "gridtopo-gui: " << e.what() << "\n";
        ok = false;
      }
    }
    if (g_opt.particles > 0) {
      f->session().slamOptions().particles = static_cast<int>(g_opt.particles);
      f->rebuildOptionGrid();
    }
    if (!g_opt.model.empty()) ok = f->openFile(g_opt.model) && ok;
    else f->openDefaultModel();
    if (g_opt.live_topology >= 0) ok = f->setLiveTopology(true, static_cast<unsigned>(g_opt.live_topology)) && ok;
    for (const auto& p : g_opt.files) ok = f->openFile(p, g_opt.resolution) && ok;
    if (!ok && scripted) {
      f->exit_code = 1;
      if (g_opt.quit) {
        f->script.clear();
        f->CallAfter([f] { f->Close(true); });
        return true;
      }
    }
    f->canvas()->layers().particle_paths = g_opt.particle_paths;
    if (!g_opt.labels.empty()) {
      try {
        f->session().openLabelImage(g_opt.labels);
      } catch (const std::exception& e) {
        std::cerr << "gridtopo-gui: " << e.what() << "\n";
        f->exit_code = 1;
      }
    }
    if (g_opt.tile_cols > 0) {
      try {
        f->session().tileMap(g_opt.tile_cols, g_opt.tile_rows);
        f->canvas()->fit();
      } catch (const std::exception& e) {
        std::cerr << "gridtopo-gui: " << e.what() << "\n";
        f->exit_code = 1;
      }
    }
    // The scripted steps, polled every timer tick (the window keeps redrawing meanwhile).
    auto& sc = f->script;
    if (g_opt.run_steps >= 0 || g_opt.run_to_end) {
      auto t_start = std::make_shared<std::chrono::steady_clock::time_point>();
      sc.push_back([f, t_start] {
        *t_start = std::chrono::steady_clock::now();
        f->startSlam();
        auto* r = f->session().runner();
        if (!r) return true;
        if (g_opt.run_to_end) r->play();
        else r->step(static_cast<std::size_t>(g_opt.run_steps));
        return true;
      });
      sc.push_back(waitIdle(f));
      sc.push_back([f] {  // the live topology of the idle run's map
        const auto* live = f->session().liveTopology();
        return !live || live->waitIdle(std::chrono::milliseconds(0));
      });
      sc.push_back([f, t_start] {
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - *t_start).count();
        f->canvas()->fit();
        f->refreshNow();
        if (auto s = f->session().slamSnapshot())
          std::cerr << "gridtopo-gui: " << s->scans_fed << " scans, " << s->steps << " updates, run " << wall
                    << " s wall (" << s->wall_seconds << " s in the filter), " << f->canvas()->frames
                    << " frames drawn, peak RSS " << s->peak_rss_bytes / 1048576 << " MB, state "
                    << session::toString(s->state) << "\n";
        if (const auto live = f->session().liveTopologyResult())
          std::cerr << "gridtopo-gui: live " << session::liveTopologyCaption(*live) << ", " << live->seconds
                    << " s; " << f->session().liveTopology()->computed() << " computed, "
                    << f->session().liveTopology()->dropped() << " dropped\n";
        return true;
      });
    }
    if (!g_opt.save_slam.empty()) sc.push_back([f] {
      try {
        f->session().saveSlamOutputs(g_opt.save_slam);
      } catch (const std::exception& e) {
        std::cerr << "gridtopo-gui: " << e.what() << "\n";
        f->exit_code = 1;
      }
      return true;
    });
    if (g_opt.use_slam_map) sc.push_back([f] {
      try {
        f->session().useSlamMap();
      } catch (const std::exception& e) {
        std::cerr << "gridtopo-gui: " << e.what() << "\n";
        f->exit_code = 1;
      }
      return true;
    });
    if (g_opt.run_topology) {
      sc.push_back([f] {
        f->startTopology();
        return true;
      });
      sc.push_back([f] { return !f->topologyRunning(); });
      sc.push_back([f] {
        if (!f->session().topology()) f->exit_code = 1;
        return true;
      });
    }
    if (!g_opt.view.empty()) sc.push_back([f] {
      f->setView(g_opt.view == "topology" ? session::ViewMode::Topology
                 : g_opt.view == "labels" ? session::ViewMode::Labels
                                          : session::ViewMode::Slam);
      return true;
    });
    if (g_opt.click_col >= 0 || g_opt.click_particle) {
      // A real mouse click through the window system (XTest under Xvfb) on the cell's screen position.
      auto state = std::make_shared<int>(0);
      sc.push_back([f, state] {
        const auto& m = f->session().topology() && f->canvas()->mode() == session::ViewMode::Topology
                            ? f->session().topology()->map
                            : f->session().map();
        const auto snap = f->session().slamSnapshot();
        if (g_opt.click_particle ? !snap || snap->particles.empty() : m.empty()) {
          std::cerr << "gridtopo-gui: nothing to click\n";
          f->exit_code = 1;
          return true;
        }
        if (*state == 0) {
          f->refreshNow();
          cv::Point2d w;
          if (g_opt.click_particle) {
            const auto& p = snap->particles[snap->best].pose;
            w = {p.x, p.y};
          } else {
            w = m.cellCentre(g_opt.click_row, g_opt.click_col);
          }
          const wxPoint p = f->canvas()->ClientToScreen(f->canvas()->toClient(w.x, w.y));
          wxUIActionSimulator sim;
          sim.MouseMove(p);
          wxYield();
          sim.MouseClick();
          ++*state;
          return false;
        }
        return ++*state > 5;  // a few ticks for the click to be delivered and handled
      });
      if (!g_opt.inspector_out.empty())
        sc.push_back([f] {
          std::ofstream(g_opt.inspector_out) << f->inspectorText();
          return true;
        });
    }
    if (g_opt.bench_frames > 0) sc.push_back([f] { return benchFrames(f, g_opt.bench_frames, g_opt.bench_out); });
    if (!g_opt.export_view.empty()) sc.push_back([f] {
      f->refreshNow();
      if (!cv::imwrite(g_opt.export_view, f->canvas()->renderImage())) f->exit_code = 1;
      return true;
    });
    if (g_opt.show_options) sc.push_back([f] {
      f->showOptionsTab();
      return true;
    });
    if (!g_opt.screenshot.empty()) sc.push_back([f] {
      if (!f->screenshot(g_opt.screenshot)) {
        std::cerr << "gridtopo-gui: cannot write " << g_opt.screenshot << "\n";
        f->exit_code = 1;
      }
      return true;
    });
    return true;
  }
  gui::MainFrame* frame_ = nullptr;
};

wxIMPLEMENT_APP_NO_MAIN(GuiApp);

int main(int argc, char** argv) {
  try {
    TCLAP::CmdLine cmd(
        "Desktop app to run and watch the RBPF SLAM, run the place labelling and topology, inspect cells, graph "
        "nodes and particles, and paint training labels. Files given on the command line are opened like File > "
        "Open (logs .clf/.log/.gz/.rawlog, maps .png/.pgm/.yaml/.gridmap(.gz), trajectories .txt, .relations(.gz), "
        "topology .json/.graphml, place models, INI files). The --run-*/--click-cell/--screenshot/--quit options "
        "script the window for tests and benchmarks.",
        ' ', "0.1");
    TCLAP::UnlabeledMultiArg<std::string> files("files", "files to open", false, "file", cmd);
    TCLAP::ValueArg<std::string> ini("c", "ini", "SLAM INI file ([slam] section, config-ini/slam.ini)", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> model("m", "model",
                                       "place model (gridtopo-train output); default: the shipped "
                                       "models/places_model.yml from $GRIDTOPO_DATA_DIR, beside the executable "
                                       "(../share/gridtopo/datasets, ../datasets) or the source tree",
                                       false, "", "file", cmd);
    TCLAP::ValueArg<std::string> tini("", "topology-ini", "topology INI (config-ini/topology.ini)", false, "", "file", cmd);
    TCLAP::ValueArg<double> res("r", "resolution", "metres per pixel of plain map images (no prompt)", false, 0, "m", cmd);
    TCLAP::ValueArg<long> max_scans("", "max-scans", "use only the first n scans of the log", false, 0, "n", cmd);
    TCLAP::ValueArg<long> particles("p", "particles", "number of particles (overrides the INI)", false, 0, "n", cmd);
    TCLAP::ValueArg<long> run_steps("", "run-steps", "start the SLAM and run n filter updates", false, -1, "n", cmd);
    TCLAP::SwitchArg run_end("", "run-to-end", "start the SLAM and run it to the end of the log", cmd);
    TCLAP::ValueArg<long> live("", "live-topology",
                               "turn on the live topology of the SLAM run: the labels and graph of the best map every "
                               "n updates and when the run pauses or ends (0: only then)",
                               false, -1, "n", cmd);
    TCLAP::SwitchArg slam_map("", "use-slam-map", "after the run, send the SLAM map to the topology view", cmd);
    TCLAP::SwitchArg run_topo("", "run-topology", "run labelling + topology on the current map", cmd);
    TCLAP::ValueArg<std::string> view("", "view", "slam | topology | labels", false, "", "name", cmd);
    TCLAP::ValueArg<std::string> click("", "click-cell", "click the map cell col,row with the mouse simulator", false, "",
                                       "col,row", cmd);
    TCLAP::ValueArg<std::string> insp("", "inspector-out", "write the inspector text after --click-cell", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> shot("", "screenshot", "save a screenshot of the window (PNG)", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> exportv("", "export-view", "save the map view (PNG)", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> size("", "size", "window size WxH", false, "1280x860", "WxH", cmd);
    TCLAP::ValueArg<int> bench("", "bench-frames", "pan/zoom for n frames and print the frame rate", false, 0, "n", cmd);
    TCLAP::ValueArg<std::string> save_slam("", "save-slam", "after the run, save the SLAM outputs to this directory",
                                           false, "", "dir", cmd);
    TCLAP::SwitchArg show_options("", "show-options", "show the SLAM options tab", cmd);
    TCLAP::SwitchArg paths("", "particle-paths", "show every particle's trajectory", cmd);
    TCLAP::SwitchArg click_particle("", "click-particle", "click the best particle with the mouse simulator", cmd);
    TCLAP::ValueArg<std::string> labels("", "labels", "open a labelled image (77/115/179/0) in the label painter",
                                        false, "", "file", cmd);
    TCLAP::ValueArg<std::string> tile("", "tile-map", "replace the map by a WxH-cell tiling of itself (benchmark)", false,
                                      "", "WxH", cmd);
    TCLAP::ValueArg<std::string> bench_out("", "bench-out", "append the benchmark line to this file", false, "", "file", cmd);
    TCLAP::SwitchArg quit("", "quit", "quit when the scripted steps are done", cmd);
    cmd.parse(argc, argv);
    g_opt.files = files.getValue();
    g_opt.ini = ini.getValue();
    g_opt.model = model.getValue();
    g_opt.topology_ini = tini.getValue();
    g_opt.resolution = res.getValue();
    if (res.isSet() && !(res.getValue() > 0)) throw InputError("--resolution", "must be > 0");
    g_opt.max_scans = max_scans.getValue();
    g_opt.particles = particles.getValue();
    g_opt.run_steps = run_steps.getValue();
    g_opt.run_to_end = run_end.getValue();
    if (live.isSet() && (live.getValue() < 0 || live.getValue() > 1000000))
      throw InputError("--live-topology", "must be in [0, 1000000], got " + std::to_string(live.getValue()));
    g_opt.live_topology = live.getValue();
    g_opt.use_slam_map = slam_map.getValue();
    g_opt.run_topology = run_topo.getValue();
    g_opt.view = view.getValue();
    if (!g_opt.view.empty() && g_opt.view != "slam" && g_opt.view != "topology" && g_opt.view != "labels")
      throw InputError("--view", "must be slam, topology or labels");
    if (click.isSet() && std::sscanf(click.getValue().c_str(), "%d,%d", &g_opt.click_col, &g_opt.click_row) != 2)
      throw InputError("--click-cell", "expected col,row");
    g_opt.inspector_out = insp.getValue();
    g_opt.screenshot = shot.getValue();
    g_opt.export_view = exportv.getValue();
    // "WxH" with both in [lo, hi], or an error naming the option.
    auto parseWxH = [](const TCLAP::ValueArg<std::string>& a, int lo, int hi, int& w, int& h) {
      if (std::sscanf(a.getValue().c_str(), "%dx%d", &w, &h) != 2 || w < lo || h < lo || w > hi || h > hi)
        throw InputError("--" + a.getName(), "expected WxH, both in " + std::to_string(lo) + ".." + std::to_string(hi));
    };
    parseWxH(size, 200, 100000, g_opt.width, g_opt.height);
    g_opt.bench_frames = bench.getValue();
    g_opt.bench_out = bench_out.getValue();
    g_opt.particle_paths = paths.getValue();
    g_opt.show_options = show_options.getValue();
    g_opt.save_slam = save_slam.getValue();
    g_opt.click_particle = click_particle.getValue();
    g_opt.labels = labels.getValue();
    if (tile.isSet()) parseWxH(tile, 1, 20000, g_opt.tile_cols, g_opt.tile_rows);
    g_opt.quit = quit.getValue();
  } catch (const TCLAP::ArgException& e) {
    std::cerr << "gridtopo-gui: " << e.argId() << ": " << e.error() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "gridtopo-gui: error: " << e.what() << "\n";
    return 1;
  }
  // wx must not parse our options: give it the program name only.
  int wx_argc = 1;
  char* wx_argv[] = {argv[0], nullptr};
  const int rc = wxEntry(wx_argc, wx_argv);
  return rc != 0 ? rc : g_exit_code;
}
