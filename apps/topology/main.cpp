// gridtopo-topology: occupancy map -> semantic place labels -> regions -> topological graph, with exports
// (GraphML, JSON, DOT, PNG overlay, label image in the 77/115/179/0 code, room-segmentation image).
#include <tclap/CmdLine.h>

#include <iostream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/bulk_allocator.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/core/run_args.h"
#include "gridtopo/topology/topology_map_run.h"

using namespace gridtopo;

int main(int argc, char** argv) {
  // A large map's pipeline allocates and frees images of the whole map many times over: reusing the freed memory
  // instead of faulting in fresh pages each time saves most of the system time (doc/topology.md, Speed).
  keepFreedMemoryForReuse();
  adviseHugePagesForLargeImages();  // full-map images on 2 MiB pages: fewer page faults and TLB misses
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
    TCLAP::ValueArg<std::string> model_arg("m", "model", "place model from gridtopo-train; default: the shipped models/places_model.yml, "
                                           "from $GRIDTOPO_DATA_DIR, beside the executable or the source tree", false,
                                           topology::kDefaultPlacesModel, "file", cmd);
    TCLAP::ValueArg<std::string> ini("c", "ini", "INI file (config-ini/topology.ini)", false, "", "file", cmd);
    TCLAP::ValueArg<double> res("r", "resolution", "metres per pixel for plain images (overrides the INI)", false, 0,
                                "m", cmd);
    TCLAP::ValueArg<int> threads("", "threads", "worker threads (overrides the INI)", false, 0, "n", cmd);
    TCLAP::ValueArg<std::string> out("o", "output", "output directory", false, "", "dir", cmd);
    TCLAP::ValueArg<std::string> traj("t", "trajectory",
                                      "the robot's trajectory in the map's frame (gridtopo-slam's trajectory.txt): "
                                      "free space it did not see from near or cannot reach is no place",
                                      false, "", "file", cmd);
    HelpOptionsArg help_options(cmd, topology::topologyRunOptionsHelp);
    TCLAP::SwitchArg quiet("q", "quiet", "no progress bar", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    const topology::TopologyRunSpec spec = topology::topologyRunOfCommandLine(
        positionalArgument(map_arg), given(ini), {given(model_arg), given(out), given(traj), given(res), given(threads)});
    topology::runTopologyOnMapFile(spec, quiet.getValue(), std::cerr);
    return 0;
  });
}
