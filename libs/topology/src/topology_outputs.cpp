#include "gridtopo/topology/topology_outputs.h"

#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "gridtopo/core/output_set.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/mrpt_graph.h"
#include "gridtopo/topology/segmentation.h"

namespace gridtopo::topology {

void writeTopologyOutputs(const std::string& dir, const places::OccupancyImage& occ, const TopologyResult& topo,
                          const cv::Mat& labels_before_correction, int overlay_scale, const std::string& options_ini) {
  OutputSet outs(dir);
  addTopologyOutputs(outs, dir, occ, topo, labels_before_correction, overlay_scale, options_ini);
  outs.commit();
}

void addTopologyOutputs(OutputSet& outs, const std::string& dir, const places::OccupancyImage& occ,
                        const TopologyResult& topo, const cv::Mat& labels_before_correction, int overlay_scale,
                        const std::string& options_ini) {
  outs.write(dir + "/topology.graphml", [&](const std::string& p) { writeTextFileAtomically(p, toGraphML(topo.graph)); });
  outs.write(dir + "/topology.json", [&](const std::string& p) { writeTextFileAtomically(p, toJson(topo.graph)); });
  outs.write(dir + "/topology.dot", [&](const std::string& p) { writeTextFileAtomically(p, toDot(topo.graph)); });
  outs.write(dir + "/topology_posegraph.graph",
             [&](const std::string& p) { toMrptPoseGraph(topo.graph).saveToTextFile(p); });
  auto png = [&](const std::string& name, const cv::Mat& img) {
    outs.write(dir + "/" + name, [&](const std::string& p) {
      if (!cv::imwrite(p, img)) throw std::runtime_error("cannot write " + p);
    });
  };
  // The result's images may cover the box of the places only (TopologyResult::frame): every image written is the
  // whole map's.
  const cv::Point frame = topo.frame.tl();
  const cv::Size map_size = topo.map_size.empty() ? topo.labels.size() : topo.map_size;
  png("overlay.png",
      renderOverlay(occ, topo.labels, topo.regions, topo.graph, overlay_scale, &topo.door_passages, frame));
  png("labels.png", places::labelsToCodes(topo.inMap(topo.labels, places::kNoLabel)));
  if (!labels_before_correction.empty())
    png("labels_before_correction.png", places::labelsToCodes(labels_before_correction));
  if (!topo.segmentation.empty()) {
    png("segmentation.png", segmentationImage16(topo.segmentation, frame, map_size));
    png("segmentation_colour.png", colourSegmentation(topo.segmentation, frame, map_size));
  }
  outs.write(dir + "/options.ini", [&](const std::string& p) { writeTextFileAtomically(p, options_ini); });
}

}  // namespace gridtopo::topology
