// gridtopo-topology-compare: scores a gridtopo-topology result against a labelled reference map of the same
// building drawn in another frame (e.g. the Intel map of gridtopo-slam against the lab_intel floor plan):
// aligns the two free spaces (topology/reference_alignment.h), then reports cell-label accuracy and room
// segmentation precision / recall on the map's free cells, as JSON, with an overlay PNG to look at.
#include <tclap/CmdLine.h>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/occupancy.h"
#include "gridtopo/topology/evaluation.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/graph_evaluation.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/topology/reference_alignment.h"

using namespace gridtopo;

namespace {
cv::Mat readImage(const std::string& path, int flags) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "file not found");
  cv::Mat m = cv::imread(path, flags);
  if (m.empty()) throw InputError(path, "cannot read the image (missing file or unknown format)");
  return m;
}
std::string pct(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << 100 * v;
  return s.str();
}
}  // namespace

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-topology-compare", [&]() -> int {
    TCLAP::CmdLine cmd(
        "Score a gridtopo-topology output directory (labels.png, segmentation.png) against a labelled reference map "
        "of the same building in another frame: the reference is aligned to the map (affine ECC on the free "
        "spaces), then cell-label accuracy and room-segmentation precision / recall are computed on the map's free "
        "cells.",
        ' ', "0.1");
    TCLAP::UnlabeledValueArg<std::string> map_arg("map", "the map that was labelled (.yaml, .gridmap(.gz), image)",
                                                  true, "", "map", cmd);
    TCLAP::UnlabeledValueArg<std::string> dir_arg("topology", "gridtopo-topology output directory", true, "", "dir",
                                                  cmd);
    TCLAP::ValueArg<std::string> ref_map("", "reference-map", "reference floor plan (free = grey > 250)", true, "",
                                         "png", cmd);
    TCLAP::ValueArg<std::string> ref_labels("", "reference-labels",
                                            "reference labels (room 77, corridor 115, doorway 179), same frame", true,
                                            "", "png", cmd);
    TCLAP::ValueArg<std::string> ref_seg("", "reference-segmentation",
                                         "reference room-segmentation ground truth (rooms white), same frame", true,
                                         "", "png", cmd);
    TCLAP::ValueArg<std::string> ini("c", "ini", "topology INI (free thresholds of the map)", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> json("j", "json", "write the scores as JSON here", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> overlay("", "overlay",
                                         "write a PNG: our segments in colours, reference room borders in red", false,
                                         "", "png", cmd);
    TCLAP::ValueArg<std::string> errors("", "errors",
                                        "write a PNG of the label errors (wrong cells in the predicted label's colour)",
                                        false, "", "png", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    const topology::TopologyOptions opt = topology::loadTopologyOptions(ini.getValue());
    const auto grid = io::readGridMap(map_arg.getValue(), io::MapReadOptions{});
    // The map's free cells as thresholded, without the free-space opening: the scored area does not depend on it.
    const places::OccupancyImage occ =
        places::occupancyFromGrey(io::gridToImage(*grid), grid->getResolution(), map_arg.getValue(),
                                  opt.freeThresholdFor(io::mapFileKind(map_arg.getValue())));
    const cv::Mat map_free = occ.cells == places::kFree;

    const std::string dir = dir_arg.getValue();
    const cv::Mat codes = readImage(dir + "/labels.png", cv::IMREAD_GRAYSCALE);
    const cv::Mat seg16 = readImage(dir + "/segmentation.png", cv::IMREAD_UNCHANGED);
    if (codes.size() != map_free.size() || seg16.size() != map_free.size())
      throw InputError(dir, "labels.png / segmentation.png are not the size of the map (" +
                                std::to_string(map_free.cols) + "x" + std::to_string(map_free.rows) + ")");
    const cv::Mat labels = places::labelsFromCodes(codes);
    cv::Mat seg;
    seg16.convertTo(seg, CV_32S);

    const cv::Mat rmap = readImage(ref_map.getValue(), cv::IMREAD_GRAYSCALE);
    const cv::Mat rcodes = readImage(ref_labels.getValue(), cv::IMREAD_GRAYSCALE);
    const cv::Mat rooms = topology::groundTruthRooms(readImage(ref_seg.getValue(), cv::IMREAD_UNCHANGED));
    if (rcodes.size() != rmap.size() || rooms.size() != rmap.size())
      throw InputError(ref_labels.getValue(), "reference map, labels and segmentation differ in size");
    const cv::Mat ref_free = rmap > 250;

    const auto s = topology::scoreAgainstReference(map_free, labels, seg, ref_free, rcodes, rooms, 100, ref_map.getValue());
    const auto& a = s.alignment;
    // The graph as gridtopo-topology built it from labels.png (the same INI is needed: checked on topology.json).
    const auto gc = topology::compareGraphWithPlan(map_free, labels, grid->getResolution(), opt, ref_free, rcodes, rooms, a);
    const auto &gs = gc.score, &gs_ceiling = gc.plan_labels;
    if (std::filesystem::is_regular_file(dir + "/topology.json")) {
      const auto written = topology::graphFromJson(dir + "/topology.json");
      if (written.nodes.size() != gc.graph.nodes.size() || written.edges.size() != gc.graph.edges.size())
        throw InputError(dir + "/topology.json", 0, "nodes",
                         std::to_string(written.nodes.size()) + " nodes, " + std::to_string(written.edges.size()) +
                             " edges, but labels.png with this INI gives " + std::to_string(gc.graph.nodes.size()) +
                             " and " + std::to_string(gc.graph.edges.size()) + ": use the INI gridtopo-topology ran with");
    }
    std::ostringstream js;
    js << std::setprecision(6) << "{\n  \"format\": \"gridtopo-topology-compare\",\n  \"map\": \"" << map_arg.getValue()
       << "\",\n  \"alignment\": {\"correlation\": " << a.correlation << ", \"start\": " << a.start
       << ", \"map_to_reference\": [" << a.map_to_reference(0, 0) << ", " << a.map_to_reference(0, 1) << ", "
       << a.map_to_reference(0, 2) << ", " << a.map_to_reference(1, 0) << ", " << a.map_to_reference(1, 1) << ", "
       << a.map_to_reference(1, 2) << "]},\n  \"cell_accuracy\": " << s.labels.accuracy()
       << ",\n  \"labels\": " << s.labels.toJson(2) << ",\n  \"segmentation\": " << s.segmentation.toJson() << ",\n  \"graph\": " << gs.toJson()
       << ",\n  \"graph_of_plan_labels\": " << gs_ceiling.toJson() << "\n}\n";
    OutputSet outs;
    if (!json.getValue().empty())
      outs.write(json.getValue(), [&](const std::string& p) { writeTextFileAtomically(p, js.str()); });
    if (!overlay.getValue().empty()) {
      cv::Mat img = topology::colourSegmentation(seg);
      const cv::Mat r = topology::warpReferenceToMap(rooms, a, map_free.size());
      for (int y = 1; y < r.rows; ++y)
        for (int x = 1; x < r.cols; ++x)
          if (r.at<int>(y, x) != r.at<int>(y - 1, x) || r.at<int>(y, x) != r.at<int>(y, x - 1))
            img.at<cv::Vec3b>(y, x) = cv::Vec3b(0, 0, 255);
      outs.write(overlay.getValue(), [&](const std::string& p) {
        if (!cv::imwrite(p, img)) throw std::runtime_error("cannot write " + p);
      });
    }
    if (!errors.getValue().empty()) {
      cv::Mat truth = topology::warpReferenceToMap(rcodes, a, map_free.size());
      const cv::Mat img = topology::labelErrorOverlay(occ, truth, labels);
      outs.write(errors.getValue(), [&](const std::string& p) {
        if (!cv::imwrite(p, img)) throw std::runtime_error("cannot write " + p);
      });
    }
    outs.commit();
    std::cout << "alignment correlation " << std::setprecision(3) << a.correlation << "; cell accuracy "
              << pct(s.labels.accuracy()) << " % (room / corridor / doorway recall " << pct(s.labels.recall(0))
              << " / " << pct(s.labels.recall(1)) << " / " << pct(s.labels.recall(2)) << " %); segmentation: "
              << s.segmentation.segments << " segments, " << s.segmentation.rooms << " rooms, recall "
              << pct(s.segmentation.recall) << " %, precision " << pct(s.segmentation.precision) << " %; graph: "
              << gs.attached << " of " << gs.plan_rooms << " plan rooms one room node attached through a doorway ("
              << pct(gs.attachedFraction()) << " %), " << gs.loops_closed << " of " << gs.plan_loops
              << " plan corridor loops a cycle of corridor nodes (with the plan's labels: " << pct(gs_ceiling.attachedFraction())
              << " %, " << gs_ceiling.loops_closed << " of " << gs_ceiling.plan_loops << ")\n";
    return 0;
  });
}
