#pragma once
// gridtopo-gui's command line: files to open, options, and the scripted steps (--run-steps, --run-topology,
// --click-cell, --screenshot, --quit, ...) that tests and benchmarks drive the window with.
#include <string>
#include <vector>

namespace gridtopo::gui {

struct GuiArguments {
  std::vector<std::string> files;
  std::string ini, model, topology_ini, screenshot, export_view, inspector_out, view, bench_out;
  double resolution = 0;
  long max_scans = 0, run_steps = -1, particles = 0, live_topology = -1;
  bool run_to_end = false, run_topology = false, quit = false, use_slam_map = false;
  int click_col = -1, click_row = -1;
  int width = 1280, height = 860;
  int bench_frames = 0;
  int tile_cols = 0, tile_rows = 0;
  bool particle_paths = false, particle_map = false, click_particle = false, show_options = false;
  std::string labels, save_slam;
};

/// Parses the command line (TCLAP with exception handling off: TCLAP::ArgException for bad usage, ExitException
/// for --help, gridtopo::InputError naming the option for a bad value), for gridtopo::runApp.
GuiArguments parseGuiArguments(int argc, char** argv);

/// Whether any scripted step was asked for (errors then go to stderr, not to modal dialogs).
bool scripted(const GuiArguments& a);

}  // namespace gridtopo::gui
