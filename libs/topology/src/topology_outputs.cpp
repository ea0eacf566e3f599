#include "gridtopo/topology/topology_outputs.h"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <functional>
#include <stdexcept>

#include "gridtopo/core/output_set.h"
#include "gridtopo/io/image_write.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/mrpt_graph.h"
#include "mask_ops.h"
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
      topo.regions.ids.empty()
          ? renderOverlay(occ, topo.labels, topo.region_borders, topo.graph, overlay_scale, &topo.door_passages, frame)
          : renderOverlay(occ, topo.labels, topo.regions, topo.graph, overlay_scale, &topo.door_passages, frame));
  // The label and segmentation pictures row by row from the frame's images (io::writePngRows): no picture of the
  // whole map is made for them (on the hospital's map each is 56-168 MB).
  const cv::Rect inner(frame, topo.labels.size());
  const auto rows = [&](const std::string& name, int type, const std::function<void(int, unsigned char*)>& row) {
    outs.write(dir + "/" + name, [&](const std::string& p) { io::writePngRows(p, map_size, type, row); });
  };
  const auto codesRow = [&](const cv::Mat& labels, cv::Rect where) {
    return [&labels, where, &map_size](int y, unsigned char* out) {
      std::fill(out, out + map_size.width, places::kNoLabelCode);
      if (y < where.y || y >= where.y + where.height) return;
      const unsigned char* l = labels.ptr<unsigned char>(y - where.y);
      for (int x = 0; x < where.width; ++x)
        if (l[x] < places::kNumLabels) out[where.x + x] = places::labelCode(l[x]);
    };
  };
  rows("labels.png", CV_8UC1, codesRow(topo.labels, inner));
  if (!labels_before_correction.empty())
    rows("labels_before_correction.png", CV_8UC1,
         codesRow(labels_before_correction, cv::Rect(cv::Point(), labels_before_correction.size())));
  else if (!topo.labels_classified.empty())  // the caller let its labels go into the topology (topologyOfMap)
    rows("labels_before_correction.png", CV_8UC1, [&](int y, unsigned char* out) {
      topo.labels_classified.row(y, out, [](unsigned char l) {
        return l < places::kNumLabels ? places::labelCode(l) : places::kNoLabelCode;
      });
    });
  if (!topo.segmentation.empty()) {
    const cv::Rect seg(frame, topo.segmentation.size());
    requireSixteenBitSegments(topo.segmentation);
    rows("segmentation.png", CV_16UC1, [&](int y, unsigned char* out) {
      auto* o = reinterpret_cast<unsigned short*>(out);
      std::fill(o, o + map_size.width, static_cast<unsigned short>(0));
      if (y < seg.y || y >= seg.y + seg.height) return;
      for (int x = 0; x < seg.width; ++x)
        o[seg.x + x] = static_cast<unsigned short>(std::max(0, idAt(topo.segmentation, y - seg.y, x)));
    });
    rows("segmentation_colour.png", CV_8UC3, [&](int y, unsigned char* out) {
      std::fill(out, out + 3 * map_size.width, static_cast<unsigned char>(0));
      if (y < seg.y || y >= seg.y + seg.height) return;
      for (int x = 0; x < seg.width; ++x) {
        const cv::Vec3b c = segmentColour(idAt(topo.segmentation, y - seg.y, x));
        std::copy(c.val, c.val + 3, out + 3 * (seg.x + x));
      }
    });
  }
  outs.write(dir + "/options.ini", [&](const std::string& p) { writeTextFileAtomically(p, options_ini); });
}

}  // namespace gridtopo::topology
