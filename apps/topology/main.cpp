// gridtopo-topology: occupancy map -> semantic place labels -> regions -> topological graph, with exports
// (GraphML, JSON, DOT, PNG overlay, label image in the 77/115/179/0 code, room-segmentation image).
#include <tclap/CmdLine.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/places/model.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/topology/run_summary.h"
#include "gridtopo/topology/topology_outputs.h"
#include "gridtopo/topology/topology_run_ini.h"

using namespace gridtopo;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-topology", [&]() -> int {
    TCLAP::CmdLine cmd(
        "Label the places of an occupancy map (room / corridor / doorway; Mozos et al.), build regions and the "
        "topological graph, and write them to an output directory: topology.graphml, topology.json, topology.dot, "
        "overlay.png, labels.png (room 77, corridor 115, doorway 179, other 0; pixel-aligned with the input), "
        "segmentation.png (16-bit room ids, 0 = not free), segmentation_colour.png, topology_posegraph.graph (MRPT "
        "CNetworkOfPoses2D text format: nodes at their anchors inside the regions), options.ini.",
        ' ', "0.1");
    TCLAP::UnlabeledValueArg<std::string> map_arg(
        "map", "map: .png/.pgm/.jpg (+ ROS .yaml beside it), .yaml, .gridmap(.gz); or a RUN.ini ([topology_run] map, "
        "model, output and the option sections; see config-ini/run-topology.ini), which the flags override",
        true, "", "map|RUN.ini", cmd);
    TCLAP::ValueArg<std::string> model_arg("m", "model", "place model from gridtopo-train", false,
                                           topology::kDefaultPlacesModel, "file", cmd);
    TCLAP::ValueArg<std::string> ini("c", "ini", "INI file (config-ini/topology.ini)", false, "", "file", cmd);
    TCLAP::ValueArg<double> res("r", "resolution", "metres per pixel for plain images (overrides the INI)", false, 0,
                                "m", cmd);
    TCLAP::ValueArg<int> threads("", "threads", "worker threads (overrides the INI)", false, 0, "n", cmd);
    TCLAP::ValueArg<std::string> out("o", "output", "output directory", false, "", "dir", cmd);
    HelpOptionsArg help_options(cmd, topology::topologyRunOptionsHelp);
    TCLAP::SwitchArg quiet("q", "quiet", "no progress bar", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    const std::string& first = map_arg.getValue();
    // TCLAP hands an unknown flag to the positional argument.
    if (first.rfind('-', 0) == 0) throw UsageError(first + ": unknown argument");
    const bool has_run_ini = first.size() > 4 && first.compare(first.size() - 4, 4, ".ini") == 0;
    if (has_run_ini && ini.isSet()) throw UsageError("give the options either in RUN.ini or with -c, not both");
    if (!has_run_ini && !out.isSet()) throw UsageError("name the output directory (-o), or give a RUN.ini");
    topology::TopologyRunSpec spec = has_run_ini ? topology::loadTopologyRunIni(first) : topology::TopologyRunSpec{};
    if (!has_run_ini) {
      spec.map = first;
      spec.options = topology::loadTopologyOptions(ini.getValue());
    }
    const auto given = [](auto& arg) { return arg.isSet() ? std::optional(arg.getValue()) : std::nullopt; };
    topology::overrideRun(spec, {given(model_arg), given(out), given(res), given(threads)});
    const topology::TopologyOptions& opt = spec.options;
    topology::checkTopologyRunSpec(spec);
    const auto t0 = std::chrono::steady_clock::now();
    const places::PlacesModel model = places::PlacesModel::load(spec.model);

    io::MapReadOptions ro;
    ro.resolution = opt.resolution;
    const MapImage map = io::readMap(spec.map, ro);
    std::cerr << topology::resolutionWarning(map.resolution, model);

    ProgressBar bar(100, "topology", "%", quiet.getValue() ? 0 : -1);
    const auto run = topology::topologyOfMap(map, model, opt, [&](const std::string& stage, std::size_t d, std::size_t n) {
      if (stage == "scans") bar.update(d * 80 / std::max<std::size_t>(n, 1), stage);
      else bar.update(stage == "regions" ? 90 : 85, stage);
    });
    bar.update(100, "exports");
    bar.finish();

    topology::writeTopologyOutputs(spec.output, run.occ, run.topo, run.labelling.labels, opt.overlay_scale,
                                   topology::topologyRunIni(spec));
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cerr << topology::runSummary(run, spec.map, secs);
    return 0;
  });
}
