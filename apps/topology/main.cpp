// gridtopo-topology: occupancy map -> semantic place labels -> regions -> topological graph, with exports
// (GraphML, JSON, DOT, PNG overlay, label image in the 77/115/179/0 code, room-segmentation image).
#include <mrpt/config/CConfigFile.h>
#include <tclap/CmdLine.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/model.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/mrpt_graph.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/topology/segmentation.h"

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
    TCLAP::UnlabeledValueArg<std::string> map_arg("map", "map: .png/.pgm/.jpg (+ ROS .yaml beside it), .yaml, .gridmap(.gz)",
                                                  true, "", "map", cmd);
    TCLAP::ValueArg<std::string> model_arg("m", "model", "place model from gridtopo-train", false,
                                           "datasets/models/places_model.yml", "file", cmd);
    TCLAP::ValueArg<std::string> ini("c", "ini", "INI file (config-ini/topology.ini)", false, "", "file", cmd);
    TCLAP::ValueArg<double> res("r", "resolution", "metres per pixel for plain images (overrides the INI)", false, 0,
                                "m", cmd);
    TCLAP::ValueArg<int> threads("", "threads", "worker threads (overrides the INI)", false, 0, "n", cmd);
    TCLAP::ValueArg<std::string> out("o", "output", "output directory", true, "", "dir", cmd);
    TCLAP::SwitchArg quiet("q", "quiet", "no progress bar", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    topology::TopologyOptions opt = topology::loadTopologyOptions(ini.getValue());
    if (res.isSet()) {
      if (!(res.getValue() > 0)) throw InputError("--resolution", "must be > 0");
      opt.resolution = res.getValue();
    }
    if (threads.isSet()) {
      if (threads.getValue() < 1) throw InputError("--threads", "must be >= 1");
      opt.threads = threads.getValue();
    }
    const auto t0 = std::chrono::steady_clock::now();
    const places::PlacesModel model = places::PlacesModel::load(model_arg.getValue());

    io::MapReadOptions ro;
    ro.resolution = opt.resolution;
    const auto grid = io::readGridMap(map_arg.getValue(), ro);
    const cv::Mat grey = io::gridToImage(*grid);
    const io::MapKind kind = io::mapFileKind(map_arg.getValue());
    const places::OccupancyImage occ = topology::occupancyForTopology(
        grey, grid->getResolution(), map_arg.getValue(), opt.freeThresholdFor(kind), opt.freeOpeningRadiusFor(kind));
    if (occ.resolution > model.scan.lattice_spacing * 1.5 && model.scan.lattice_spacing > 0)
      std::cerr << "warning: map resolution " << occ.resolution << " m is coarser than the model's lattice ("
                << model.scan.lattice_spacing << " m); results may differ from training\n";

    ProgressBar bar(100, "topology", "%", quiet.getValue() ? 0 : -1);
    const auto lab = places::labelPlaces(occ, model, opt.relaxation, opt.threads, map_arg.getValue(),
                                         [&](const std::string& stage, std::size_t d, std::size_t n) {
                                           if (stage == "scans") bar.update(d * 80 / std::max<std::size_t>(n, 1), stage);
                                           else bar.update(85, stage);
                                         });
    bar.update(90, "regions");
    const auto topo = topology::buildTopology(lab.labels, occ.resolution, opt, &lab,
                                              cv::Point2d(grid->getXMin(), grid->getYMin()));
    bar.update(100, "exports");
    bar.finish();

    OutputSet outs;
    const std::string dir = out.getValue();
    outs.write(dir + "/topology.graphml",
               [&](const std::string& p) { writeTextFileAtomically(p, topology::toGraphML(topo.graph)); });
    outs.write(dir + "/topology.json", [&](const std::string& p) { writeTextFileAtomically(p, topology::toJson(topo.graph)); });
    outs.write(dir + "/topology.dot", [&](const std::string& p) { writeTextFileAtomically(p, topology::toDot(topo.graph)); });
    outs.write(dir + "/topology_posegraph.graph",
               [&](const std::string& p) { topology::toMrptPoseGraph(topo.graph).saveToTextFile(p); });
    auto png = [&](const std::string& name, const cv::Mat& img) {
      outs.write(dir + "/" + name, [&](const std::string& p) {
        if (!cv::imwrite(p, img)) throw std::runtime_error("cannot write " + p);
      });
    };
    png("overlay.png", topology::renderOverlay(occ, topo.labels, topo.regions, topo.graph, opt.overlay_scale));
    png("labels.png", places::labelsToCodes(topo.labels));
    png("labels_before_correction.png", places::labelsToCodes(lab.labels));
    png("segmentation.png", topology::segmentationImage16(topo.segmentation));
    png("segmentation_colour.png", topology::colourSegmentation(topo.segmentation));
    std::ostringstream used;
    opt.dumpToTextStream(used);
    outs.write(dir + "/options.ini", [&](const std::string& p) { writeTextFileAtomically(p, used.str()); });
    outs.commit();
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    int counts[3] = {0, 0, 0};
    for (const auto& n : topo.graph.nodes) counts[n.label]++;
    std::cerr << map_arg.getValue() << ": " << occ.cols() << "x" << occ.rows() << " cells, "
              << lab.lattice.samples.size() << " classified, relaxation " << lab.relaxation.iterations
              << " iterations; " << counts[0] << " rooms, " << counts[1] << " corridors, " << counts[2]
              << " doorways, " << topo.graph.edges.size() << " edges, " << topology::segmentCount(topo.segmentation)
              << " segments; " << secs << " s (scans " << lab.seconds_scans << ", features " << lab.seconds_features
              << ", classify " << lab.seconds_classify << ", relax " << lab.seconds_relax << ")\n";
    return 0;
  });
}
