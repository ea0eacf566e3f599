// gridtopo-topology-compare: scores a gridtopo-topology result against a labelled reference map of the same
// building drawn in another frame (e.g. the Intel map of gridtopo-slam against the lab_intel floor plan):
// aligns the two free spaces, then reports cell-label accuracy and room
// segmentation precision / recall and the graph against the plan on the map's free cells, as JSON, with an
// overlay PNG to look at. The measurement: eval/reference_comparison.h.
// With --reference-topology MAP DIR instead of a plan, the reference is another topology of the same building (two
// SLAM runs, one log in two layouts): labels agreement on the places both have, and the places each lacks
// (eval/topology_agreement.h).
#include <tclap/CmdLine.h>

#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/eval/reference_comparison.h"
#include "gridtopo/eval/topology_agreement.h"
#include "gridtopo/topology/topology_run_ini.h"

using namespace gridtopo;

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
    TCLAP::ValueArg<std::string> ref_map("", "reference-map", "reference floor plan (free = grey > 250)", false, "",
                                         "png", cmd);
    TCLAP::ValueArg<std::string> ref_labels("", "reference-labels",
                                            "reference labels (room 77, corridor 115, doorway 179), same frame", false,
                                            "", "png", cmd);
    TCLAP::ValueArg<std::string> ref_seg("", "reference-segmentation",
                                         "reference room-segmentation ground truth (rooms white), same frame", false,
                                         "", "png", cmd);
    TCLAP::SwitchArg same_frame("", "same-frame",
                                "the reference plan is pixel-aligned with the map (a simulated map of the plan, "
                                "gridtopo-simulate-maps): use the identity instead of searching the alignment",
                                cmd);
    TCLAP::MultiArg<std::string> ref_topo("", "reference-topology",
                                          "instead of a plan: another topology of the same building, given twice: "
                                          "its map, then its gridtopo-topology output directory",
                                          false, "path", cmd);
    TCLAP::ValueArg<std::string> traj("t", "trajectory",
                                      "the robot's trajectory in the map's frame (gridtopo-slam's trajectory.txt): "
                                      "the graph is also scored along it (plan doors crossed found as doorway nodes, "
                                      "spurious splits)",
                                      false, "", "file", cmd);
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

    // Before any computation: the options INI as strictly as gridtopo-topology -c reads it, and the outputs
    // writable.
    const topology::TopologyOptions options = topology::loadTopologyOptionsIni(ini.getValue());
    for (const auto* a : {&json, &overlay, &errors})
      if (!a->getValue().empty()) checkOutputFile(a->getValue());
    const bool plan = ref_map.isSet() || ref_labels.isSet() || ref_seg.isSet();
    if (ref_topo.isSet()) {
      if (plan) throw UsageError("give a reference plan or --reference-topology, not both");
      if (ref_topo.getValue().size() != 2)
        throw UsageError("--reference-topology is given twice: the reference's map, then its topology directory");
      const auto a = eval::compareTopologies({map_arg.getValue(), dir_arg.getValue()},
                                             {ref_topo.getValue()[0], ref_topo.getValue()[1]},
                                             options);
      if (errors.isSet()) throw UsageError("--errors needs a reference plan");
      if (traj.isSet()) throw UsageError("--trajectory needs a reference plan");
      if (same_frame.isSet()) throw UsageError("--same-frame needs a reference plan");
      OutputSet outs;
      if (!json.getValue().empty())
        outs.write(json.getValue(), [&](const std::string& p) { writeTextFileAtomically(p, eval::agreementJson(a)); });
      if (!overlay.getValue().empty())
        outs.write(overlay.getValue(), [&](const std::string& p) {
          if (!cv::imwrite(p, eval::agreementOverlay(a))) throw std::runtime_error("cannot write " + p);
        });
      outs.commit();
      std::cout << eval::agreementSummary(a) << "\n";
      return 0;
    }
    if (!ref_map.isSet() || !ref_labels.isSet() || !ref_seg.isSet())
      throw UsageError("name the reference plan (--reference-map, --reference-labels, --reference-segmentation) or "
                       "--reference-topology MAP DIR");

    const auto c = eval::compareWithReference(map_arg.getValue(), dir_arg.getValue(),
                                              {ref_map.getValue(), ref_labels.getValue(), ref_seg.getValue(),
                                               same_frame.getValue()},
                                              options, traj.getValue());
    OutputSet outs;
    const auto png = [&](const std::string& path, const cv::Mat& img) {
      outs.write(path, [&](const std::string& p) {
        if (!cv::imwrite(p, img)) throw std::runtime_error("cannot write " + p);
      });
    };
    if (!json.getValue().empty())
      outs.write(json.getValue(), [&](const std::string& p) { writeTextFileAtomically(p, eval::comparisonJson(c)); });
    if (!overlay.getValue().empty()) png(overlay.getValue(), eval::comparisonOverlay(c));
    if (!errors.getValue().empty()) png(errors.getValue(), eval::comparisonLabelErrors(c));
    outs.commit();
    std::cout << eval::comparisonSummary(c) << "\n";
    return 0;
  });
}
