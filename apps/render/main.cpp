// gridtopo-render: a map re-rendered from a SLAM trajectory at a finer resolution (the paper's Fig. 2 cut-out).
#include <tclap/CmdLine.h>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/slam/slam_run_ini.h"
#include "gridtopo/slam/trajectory_render.h"

using namespace gridtopo;

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-render", [&]() -> int {
    TCLAP::CmdLine cmd(
        "Renders the map of a log from a trajectory (gridtopo-slam's trajectory.txt) at any resolution, e.g. 1 cm per "
        "cell, with the SLAM's beam model: a window around a point, around the trajectory's first loop closure (then "
        "also how well the walls seen after the closure agree with those mapped before), or the whole map. Writes an "
        "8-bit PNG (free white, occupied black, unknown grey).", ' ', "0.1");
    TCLAP::ValueArg<std::string> input("i", "input", "the log the trajectory was built from", true, "", "file", cmd);
    TCLAP::ValueArg<std::string> traj("t", "trajectory", "trajectory (timestamp x y theta per scan)", true, "", "file", cmd);
    TCLAP::ValueArg<std::string> output("o", "output", "PNG to write", true, "", "file", cmd);
    TCLAP::ValueArg<std::string> json("j", "json", "also write the window, loop closure and agreement as JSON", false,
                                      "", "file", cmd);
    TCLAP::ValueArg<std::string> config("c", "config", "SLAM options INI (its beam and map-update options; e.g. the "
                                        "run's options.ini)", false, "", "file", cmd);
    TCLAP::ValueArg<double> resolution("r", "resolution", "m per cell", false, 0.01, "m", cmd);
    TCLAP::ValueArg<std::string> center("", "center", "window centre \"X Y\" (m, map frame)", false, "", "\"x y\"");
    TCLAP::SwitchArg loop("", "loop-closure", "window centred on the trajectory's first loop closure");
    TCLAP::SwitchArg whole("", "whole", "the whole map (mind the size at 1 cm)");
    cmd.xorAdd(std::vector<TCLAP::Arg*>{&center, &loop, &whole});
    TCLAP::ValueArg<double> size("", "size", "window width and height (m)", false, 8.0, "m", cmd);
    TCLAP::ValueArg<double> min_travel("", "min-travel", "loop closure: metres driven between the visits", false, 30.0,
                                       "m", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);
    if (resolution.getValue() <= 0 || size.getValue() <= 0) throw UsageError("--resolution and --size must be > 0");

    const slam::SlamOptions so = config.isSet() ? slam::loadSlamOptionsIni(config.getValue()) : slam::SlamOptions{};
    const auto trajectory = io::readTrajectory(traj.getValue());
    const auto scans = io::readScanLog(input.getValue());
    slam::TrajectoryRenderOptions ro;
    ro.resolution = resolution.getValue();
    ro.beams = so.beams;
    ro.map = so.map;
    nlohmann::ordered_json report{{"input", input.getValue()}, {"trajectory", traj.getValue()},
                                  {"resolution", ro.resolution}};
    cv::Mat img;
    slam::MapWindow window;
    try {
      if (loop.isSet()) {
        const auto r = slam::renderLoopClosure(scans, trajectory, ro, size.getValue(), 0.5, min_travel.getValue());
        if (!r) throw InputError(traj.getValue(), "no loop closure: the trajectory never comes back within 0.5 m of a "
                                                  "pose it left " + std::to_string(min_travel.getValue()) + " m before");
        const auto& c = r->closure;
        const auto& a = r->agreement;
        report["loop_closure"] = {{"earlier", c.earlier + 1}, {"later", c.later + 1}, {"distance_m", c.distance},
                                  {"travelled_m", c.travelled}};
        report["walls_after_vs_before"] = {{"cells", a.cells}, {"median_m", a.median}, {"p90_m", a.p90},
                                           {"within_two_cells", a.within_2cells}};
        std::cout << "first loop closure: pose " << c.later + 1 << " comes back " << c.distance << " m from pose "
                  << c.earlier + 1 << " after " << c.travelled << " m of travel; walls after it vs before: median "
                  << a.median * 100 << " cm, 90th percentile " << a.p90 * 100 << " cm, " << a.within_2cells * 100
                  << " % within two cells (" << a.cells << " cells)\n";
        window = r->window;
        img = slam::renderWindow(r->map, window);
      } else {
        if (center.isSet()) {
          std::istringstream in(center.getValue());
          double x = 0, y = 0;
          if (!(in >> x >> y)) throw UsageError("--center: expected \"X Y\", got \"" + center.getValue() + "\"");
          ro.window = slam::MapWindow::around(x, y, size.getValue(), size.getValue());
        }
        const slam::GridMap map = slam::mapFromTrajectory(scans, trajectory, ro);
        window = ro.window ? *ro.window : slam::boundsOf(map);
        img = slam::renderWindow(map, window);
      }
    } catch (const slam::TrajectoryMismatch& e) {
      throw InputError(traj.getValue(), 0, "timestamp", e.what());
    }
    report["window_m"] = {window.x0, window.y0, window.x1, window.y1};
    report["cells"] = {img.cols, img.rows};
    OutputSet out;
    out.write(output.getValue(), [&](const std::string& p) {
      if (!cv::imwrite(p, img)) throw std::runtime_error("cannot write " + p);
    });
    if (json.isSet()) out.write(json.getValue(), [&](const std::string& p) { std::ofstream(p) << report.dump(2) << "\n"; });
    out.commit();
    std::cout << "rendered " << img.cols << " x " << img.rows << " cells of " << ro.resolution << " m -> "
              << output.getValue() << "\n";
    return 0;
  });
}
