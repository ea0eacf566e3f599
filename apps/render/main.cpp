// gridtopo-render: a map re-rendered from a SLAM trajectory at a finer resolution (the paper's Fig. 2 cut-out).
#include <tclap/CmdLine.h>

#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/core/run_args.h"
#include "gridtopo/slam/render_run.h"

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
    slam::RenderRunSpec spec;
    spec.input = input.getValue(), spec.trajectory = traj.getValue(), spec.config = config.getValue();
    spec.resolution = resolution.getValue(), spec.center = given(center), spec.loop_closure = loop.isSet();
    spec.size = size.getValue(), spec.min_travel = min_travel.getValue();
    checkOutputFile(output.getValue());  // before the rendering, not after it
    if (json.isSet()) checkOutputFile(json.getValue());
    const slam::RenderRun run = slam::renderRun(spec);
    std::cout << run.loop_text;
    OutputSet out;
    out.write(output.getValue(), [&](const std::string& p) {
      if (!cv::imwrite(p, run.image)) throw std::runtime_error("cannot write " + p);
    });
    if (json.isSet())
      out.write(json.getValue(), [&](const std::string& p) {
        std::ofstream f(p);
        f << run.report_json;
        if (!f.flush()) throw std::runtime_error("cannot write " + p);
      });
    out.commit();
    std::cout << "rendered " << run.image.cols << " x " << run.image.rows << " cells of " << spec.resolution << " m -> "
              << output.getValue() << "\n";
    return 0;
  });
}
