#include "gui_script.h"

#include <wx/uiaction.h>
#include <wx/wx.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

namespace gridtopo::gui {

namespace {

const GuiArguments* g_opt = nullptr;  // the app's command line, read by the steps when they run (see startGui)

std::function<bool()> waitIdle(MainFrame* f) {
  return [f] {
    auto* r = f->session().runner();
    if (!r) return true;
    return r->waitIdle(std::chrono::milliseconds(0));
  };
}

// Frame-rate benchmark: pans and zooms the view for n frames, each fully rendered and blitted (Update() paints
// synchronously), first with the whole map in view, then zoomed to 2 screen pixels per cell.
bool benchFrames(MainFrame* f, int n, const std::string& out) {
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

void startGui(MainFrame* f, const GuiArguments& a) {
  g_opt = &a;
  const bool is_scripted = scripted(a);
  if (is_scripted) f->script.push_back([] { return true; });  // errors go to stderr, not to modal dialogs
  f->quit_when_done = g_opt->quit;
  if (g_opt->max_scans > 0) f->runner_options.max_scans = static_cast<std::size_t>(g_opt->max_scans);
  f->Show();
  bool ok = true;
  if (!g_opt->ini.empty()) ok = f->openFile(g_opt->ini) && ok;
  if (!g_opt->topology_ini.empty()) {
    try {
      f->session().openTopologyIni(g_opt->topology_ini);
      f->rebuildOptionGrid();
    } catch (const std::exception& e) {
      std::cerr << "gridtopo-gui: " << e.what() << "\n";
      ok = false;
    }
  }
  if (g_opt->particles > 0) {
    f->session().slamOptions().particles = static_cast<int>(g_opt->particles);
    f->rebuildOptionGrid();
  }
  if (!g_opt->model.empty()) ok = f->openFile(g_opt->model) && ok;
  else f->openDefaultModel();
  if (g_opt->live_topology >= 0) ok = f->setLiveTopology(true, static_cast<unsigned>(g_opt->live_topology)) && ok;
  for (const auto& p : g_opt->files) ok = f->openFile(p, g_opt->resolution) && ok;
  if (!ok && is_scripted) {
    f->exit_code = 1;
    if (g_opt->quit) {
      f->script.clear();
      f->CallAfter([f] { f->Close(true); });
      return;
    }
  }
  f->canvas()->layers().particle_paths = g_opt->particle_paths;
  f->canvas()->layers().optimised_map = !g_opt->particle_map;
  f->syncLayerMenu();
  if (!g_opt->labels.empty()) {
    try {
      f->session().openLabelImage(g_opt->labels);
    } catch (const std::exception& e) {
      std::cerr << "gridtopo-gui: " << e.what() << "\n";
      f->exit_code = 1;
    }
  }
  if (g_opt->tile_cols > 0) {
    try {
      f->session().tileMap(g_opt->tile_cols, g_opt->tile_rows);
      f->canvas()->fit();
    } catch (const std::exception& e) {
      std::cerr << "gridtopo-gui: " << e.what() << "\n";
      f->exit_code = 1;
    }
  }
  // The scripted steps, polled every timer tick (the window keeps redrawing meanwhile).
  auto& sc = f->script;
  if (g_opt->run_steps >= 0 || g_opt->run_to_end) {
    auto t_start = std::make_shared<std::chrono::steady_clock::time_point>();
    sc.push_back([f, t_start] {
      *t_start = std::chrono::steady_clock::now();
      f->startSlam();
      auto* r = f->session().runner();
      if (!r) return true;
      if (g_opt->run_to_end) r->play();
      else r->step(static_cast<std::size_t>(g_opt->run_steps));
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
  if (!g_opt->save_slam.empty()) sc.push_back([f] {
    try {
      f->session().saveSlamOutputs(g_opt->save_slam);
    } catch (const std::exception& e) {
      std::cerr << "gridtopo-gui: " << e.what() << "\n";
      f->exit_code = 1;
    }
    return true;
  });
  if (g_opt->use_slam_map) sc.push_back([f] {
    try {
      f->session().useSlamMap();
    } catch (const std::exception& e) {
      std::cerr << "gridtopo-gui: " << e.what() << "\n";
      f->exit_code = 1;
    }
    return true;
  });
  if (g_opt->run_topology) {
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
  if (!g_opt->view.empty()) sc.push_back([f] {
    f->setView(g_opt->view == "topology" ? session::ViewMode::Topology
               : g_opt->view == "labels" ? session::ViewMode::Labels
                                        : session::ViewMode::Slam);
    return true;
  });
  if (g_opt->click_col >= 0 || g_opt->click_particle) {
    // A real mouse click through the window system (XTest under Xvfb) on the cell's screen position.
    auto state = std::make_shared<int>(0);
    sc.push_back([f, state] {
      const auto& m = f->session().topology() && f->canvas()->mode() == session::ViewMode::Topology
                          ? f->session().topology()->map
                          : f->session().map();
      const auto snap = f->session().slamSnapshot();
      if (g_opt->click_particle ? !snap || snap->particles.empty() : m.empty()) {
        std::cerr << "gridtopo-gui: nothing to click\n";
        f->exit_code = 1;
        return true;
      }
      if (*state == 0) {
        f->refreshNow();
        cv::Point2d w;
        if (g_opt->click_particle) {
          const auto& p = snap->particles[snap->best].pose;
          w = {p.x, p.y};
        } else {
          w = m.cellCentre(g_opt->click_row, g_opt->click_col);
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
    if (!g_opt->inspector_out.empty())
      sc.push_back([f] {
        std::ofstream(g_opt->inspector_out) << f->inspectorText();
        return true;
      });
  }
  if (g_opt->bench_frames > 0) sc.push_back([f] { return benchFrames(f, g_opt->bench_frames, g_opt->bench_out); });
  if (!g_opt->export_view.empty()) sc.push_back([f] {
    f->refreshNow();
    if (!cv::imwrite(g_opt->export_view, f->canvas()->renderImage())) f->exit_code = 1;
    return true;
  });
  if (g_opt->show_options) sc.push_back([f] {
    f->showOptionsTab();
    return true;
  });
  if (!g_opt->screenshot.empty()) sc.push_back([f] {
    if (!f->screenshot(g_opt->screenshot)) {
      std::cerr << "gridtopo-gui: cannot write " << g_opt->screenshot << "\n";
      f->exit_code = 1;
    }
    return true;
  });
}

}  // namespace gridtopo::gui
