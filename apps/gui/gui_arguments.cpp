#include "gui_arguments.h"

#include <tclap/CmdLine.h>

#include <cstdio>
#include <filesystem>

#include "gridtopo/core/run_args.h"
#include "gridtopo/core/error.h"

namespace gridtopo::gui {

GuiArguments parseGuiArguments(int argc, char** argv) {
  GuiArguments a;
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
  TCLAP::SwitchArg particle_map("", "particle-map",
                                "show the best particle's map even once the loop closure has an optimised one", cmd);
  TCLAP::SwitchArg click_particle("", "click-particle", "click the best particle with the mouse simulator", cmd);
  TCLAP::ValueArg<std::string> labels("", "labels", "open a labelled image (77/115/179/0) in the label painter",
                                      false, "", "file", cmd);
  TCLAP::ValueArg<std::string> tile("", "tile-map", "replace the map by a WxH-cell tiling of itself (benchmark)", false,
                                    "", "WxH", cmd);
  TCLAP::ValueArg<std::string> bench_out("", "bench-out", "append the benchmark line to this file", false, "", "file", cmd);
  TCLAP::SwitchArg quit("", "quit", "quit when the scripted steps are done", cmd);
  cmd.setExceptionHandling(false);
  cmd.parse(argc, argv);
  a.files = files.getValue();
  // An unknown option lands in the file list; a file that exists may start with '-'.
  for (const std::string& f : a.files)
    if (!std::filesystem::exists(f)) rejectUnknownFlag(f);
  a.ini = ini.getValue();
  a.model = model.getValue();
  a.topology_ini = tini.getValue();
  a.resolution = res.getValue();
  if (res.isSet() && !(res.getValue() > 0)) throw InputError("--resolution", "must be > 0");
  a.max_scans = max_scans.getValue();
  a.particles = particles.getValue();
  a.run_steps = run_steps.getValue();
  a.run_to_end = run_end.getValue();
  if (live.isSet() && (live.getValue() < 0 || live.getValue() > 1000000))
    throw InputError("--live-topology", "must be in [0, 1000000], got " + std::to_string(live.getValue()));
  a.live_topology = live.getValue();
  a.use_slam_map = slam_map.getValue();
  a.run_topology = run_topo.getValue();
  a.view = view.getValue();
  if (!a.view.empty() && a.view != "slam" && a.view != "topology" && a.view != "labels")
    throw InputError("--view", "must be slam, topology or labels");
  if (click.isSet() && std::sscanf(click.getValue().c_str(), "%d,%d", &a.click_col, &a.click_row) != 2)
    throw InputError("--click-cell", "expected col,row");
  a.inspector_out = insp.getValue();
  a.screenshot = shot.getValue();
  a.export_view = exportv.getValue();
  // "WxH" with both in [lo, hi], or an error naming the option.
  auto parseWxH = [](const TCLAP::ValueArg<std::string>& a, int lo, int hi, int& w, int& h) {
    if (std::sscanf(a.getValue().c_str(), "%dx%d", &w, &h) != 2 || w < lo || h < lo || w > hi || h > hi)
      throw InputError("--" + a.getName(), "expected WxH, both in " + std::to_string(lo) + ".." + std::to_string(hi));
  };
  parseWxH(size, 200, 100000, a.width, a.height);
  a.bench_frames = bench.getValue();
  a.bench_out = bench_out.getValue();
  a.particle_paths = paths.getValue();
  a.particle_map = particle_map.getValue();
  a.show_options = show_options.getValue();
  a.save_slam = save_slam.getValue();
  a.click_particle = click_particle.getValue();
  a.labels = labels.getValue();
  if (tile.isSet()) parseWxH(tile, 1, 20000, a.tile_cols, a.tile_rows);
  a.quit = quit.getValue();
  return a;
}

bool scripted(const GuiArguments& a) {
  return a.run_steps >= 0 || a.run_to_end || a.run_topology || !a.screenshot.empty() || a.click_col >= 0 || a.quit ||
         a.bench_frames > 0;
}

}  // namespace gridtopo::gui
