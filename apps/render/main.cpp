// gridtopo-render: a map re-rendered from a SLAM trajectory at a finer resolution (the paper's Fig. 2 cut-out).
#include <tclap/CmdLine.h>

#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/slam/slam_run_ini.h"
#include "gridtopo/slam/trajectory_render.h"

using namespace gridtopo;

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-render", [&]() -> int {
    TCLAP::CmdLine cmd(
        "Renders the map of a log from a trajectory (gridtopo-slam's trajectory.txt) at any resolution, e.g. 1 cm "
        "per cell, with the SLAM's beam model: a window around a point, or around the trajectory's first loop "
        "closure, or the whole map. Writes an 8-bit PNG (free white, occupied black, unknown grey).",
        ' ', "0.1");
    TCLAP::ValueArg<std::string> input("i", "input", "the log the trajectory was built from", true, "", "file", cmd);
    TCLAP::ValueArg<std::string> traj("t", "trajectory", "trajectory file (timestamp x y theta per scan)", true, "",
                                      "file", cmd);
    TCLAP::ValueArg<std::string> output("o", "output", "PNG to write", true, "", "file", cmd);
    TCLAP::ValueArg<std::string> config("c", "config", "SLAM options INI (beam and map-update options; e.g. the "
                                        "run's options.ini)", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> section("", "section", "INI section of the options", false, "slam", "name", cmd);
    TCLAP::ValueArg<double> resolution("r", "resolution", "m per cell", false, 0.01, "m", cmd);
    TCLAP::ValueArg<std::string> center("", "center", "window centre \"X Y\" (m, map frame)", false, "", "\"x y\"");
    TCLAP::SwitchArg loop("", "loop-closure", "window centred on the trajectory's first loop closure");
    TCLAP::SwitchArg whole("", "whole", "the whole map (mind the size at 1 cm)");
    cmd.xorAdd(std::vector<TCLAP::Arg*>{&center, &loop, &whole});
    TCLAP::ValueArg<double> size("", "size", "window width and height (m)", false, 8.0, "m", cmd);
    TCLAP::ValueArg<double> min_travel("", "min-travel", "loop closure: metres driven between the two visits", false,
                                       30.0, "m", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);
    if (resolution.getValue() <= 0 || size.getValue() <= 0) throw UsageError("--resolution and --size must be > 0");

    slam::SlamOptions so;
    if (config.isSet()) so = slam::loadSlamOptionsIni(config.getValue(), section.getValue());
    const auto trajectory = io::readTrajectory(traj.getValue());
    if (trajectory.empty()) throw InputError(traj.getValue(), "the trajectory holds no pose");
    const auto scans = io::readScanLog(input.getValue());

    slam::TrajectoryRenderOptions ro;
    ro.resolution = resolution.getValue();
    ro.beams = so.beams;
    ro.map = so.map;
    if (center.isSet()) {
      std::istringstream in(center.getValue());
      double x, y;
      if (!(in >> x >> y)) throw UsageError("--center: expected \"X Y\", got \"" + center.getValue() + "\"");
      ro.window = slam::MapWindow::around(x, y, size.getValue(), size.getValue());
    } else if (loop.isSet()) {
      const auto lc = slam::firstLoopClosure(trajectory, 0.5, min_travel.getValue());
      if (!lc) throw InputError(traj.getValue(), "the trajectory never comes back within 0.5 m of a pose left " +
                                                     std::to_string(min_travel.getValue()) + " m before");
      const auto& p = trajectory[lc->later].pose;
      std::cout << "first loop closure: pose " << lc->later + 1 << " (t = " << io::formatDouble(trajectory[lc->later].timestamp)
                << ") at (" << p.x << ", " << p.y << ") comes back " << lc->distance << " m from pose " << lc->earlier + 1
                << " after " << lc->travelled << " m of travel\n";
      ro.window = slam::MapWindow::around(p.x, p.y, size.getValue(), size.getValue());
      // The paper's claim in a number: the walls seen after coming back against those mapped before.
      slam::TrajectoryRenderOptions before = ro, after = ro;
      before.end_pose = after.first_pose = lc->later;
      const auto agree = slam::wallAgreement(slam::mapFromTrajectory(scans, trajectory, before),
                                             slam::mapFromTrajectory(scans, trajectory, after), *ro.window);
      std::cout << "walls after the loop closure vs before: " << agree.cells << " occupied cells, median distance "
                << agree.median * 100 << " cm, 90th percentile " << agree.p90 * 100 << " cm, "
                << agree.within_2cells * 100 << " % within two cells\n";
    }
    std::size_t inserted = 0;
    slam::GridMap map = [&] {
      try {
        return slam::mapFromTrajectory(scans, trajectory, ro, &inserted);
      } catch (const slam::TrajectoryMismatch& e) {
        throw InputError(traj.getValue(), 0, "timestamp", e.what());
      }
    }();
    slam::MapWindow w;
    if (ro.window) {
      w = *ro.window;
    } else {
      int x0, y0, x1, y1;
      map.cellBounds(x0, y0, x1, y1);
      w = {x0 * ro.resolution, y0 * ro.resolution, x1 * ro.resolution, y1 * ro.resolution};
    }
    const cv::Mat img = slam::renderWindow(map, w);
    OutputSet out;
    out.write(output.getValue(), [&](const std::string& p) {
      if (!cv::imwrite(p, img)) throw std::runtime_error("cannot write " + p);
    });
    out.commit();
    std::cout << "rendered " << inserted << " of " << trajectory.size() << " scans: window x " << w.x0 << ".." << w.x1
              << " m, y " << w.y0 << ".." << w.y1 << " m, " << img.cols << " x " << img.rows << " cells of "
              << ro.resolution << " m -> " << output.getValue() << "\n";
    return 0;
  });
}
