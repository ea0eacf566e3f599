#include "gridtopo/session/topology_drawing.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "gridtopo/topology/export.h"

namespace gridtopo::session {

cv::Mat topologyImage(const TopologyData& t, LabelStage stage, bool with_labels) {
  const cv::Mat* labels = with_labels ? &t.labels(stage) : nullptr;
  if (!labels || labels->empty()) return greyToBgr(t.map.grey);
  cv::Mat conf;
  if (t.has_labelling) {
    const auto& lab = t.labelling;
    const cv::Mat& probs = stage == LabelStage::Classified ? lab.probs_initial : lab.probs;
    conf = cv::Mat(labels->size(), CV_32F, cv::Scalar(1));
    for (int r = 0; r < conf.rows; ++r)
      for (int c = 0; c < conf.cols; ++c) {
        const unsigned char l = labels->at<unsigned char>(r, c);
        if (l > 2) continue;
        const int b = lab.lattice.sampleOfPixel(r, c);
        if (b < 0) continue;
        conf.at<float>(r, c) = probs.at<cv::Vec3f>(lab.lattice.blocks[static_cast<std::size_t>(b)])[l];
      }
  }
  cv::Mat img = labelOverlay(t.map.grey, *labels, conf);
  // Free cells that the map preparation found to be no place, as overlay.png draws them.
  if (t.occ.cells.size() == img.size())
    for (int r = 0; r < img.rows; ++r)
      for (int c = 0; c < img.cols; ++c)
        if (t.occ.cells.at<unsigned char>(r, c) == places::kSeen) img.at<cv::Vec3b>(r, c) = topology::seenNotPlaceColour(c, r);
  return img;
}

void drawTopologyGraph(cv::Mat& screen, const ViewTransform& v, const TopologyData& t, bool graph, bool region_ids) {
  const auto& g = t.topo.graph;
  if (graph) {
    for (const auto& e : g.edges) {
      const auto *a = g.node(e.a), *b = g.node(e.b);
      if (!a || !b) continue;
      if (e.path_px.size() >= 2) {  // as in overlay.png: along the routed free path
        std::vector<cv::Point> line;
        for (const cv::Point& q : e.path_px) {
          const cv::Point2d w = pixelWorld(t, cv::Point2d(q));
          const cv::Point2d s = v.toScreen(w.x, w.y);
          line.emplace_back(static_cast<int>(std::lround(s.x)), static_cast<int>(std::lround(s.y)));
        }
        cv::polylines(screen, line, false, cv::Scalar(20, 20, 20), 2, cv::LINE_AA);
        continue;
      }
      const cv::Point2d wa = nodeAnchorWorld(t, *a), wb = nodeAnchorWorld(t, *b);
      const cv::Point2d pa = v.toScreen(wa.x, wa.y), pb = v.toScreen(wb.x, wb.y);
      if (!t.has_labelling) {  // a loaded graph has no contact points: straight lines
        cv::line(screen, pa, pb, cv::Scalar(20, 20, 20), 2, cv::LINE_AA);
        continue;
      }
      // As in overlay.png: node -> contact point -> node, leaving out the half at a node whose centroid lies
      // outside its region (a corridor loop), where a straight line would cross walls.
      const cv::Point2d wc = pixelWorld(t, e.contact_px);
      const cv::Point2d pc = v.toScreen(wc.x, wc.y);
      if (a->centroid_inside) cv::line(screen, pa, pc, cv::Scalar(20, 20, 20), 2, cv::LINE_AA);
      if (b->centroid_inside) cv::line(screen, pb, pc, cv::Scalar(20, 20, 20), 2, cv::LINE_AA);
      cv::circle(screen, pc, 2, cv::Scalar(20, 20, 20), cv::FILLED, cv::LINE_AA);
    }
    for (const auto& n : g.nodes) {
      const cv::Point2d w = nodeAnchorWorld(t, n);
      const cv::Point2d p = v.toScreen(w.x, w.y);
      cv::circle(screen, p, 6, labelColour(n.label), cv::FILLED, cv::LINE_AA);
      cv::circle(screen, p, 6, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
  }
  if (region_ids)
    for (const auto& n : g.nodes) {
      const cv::Point2d w = nodeAnchorWorld(t, n);
      const cv::Point2d p = v.toScreen(w.x, w.y);
      cv::putText(screen, std::to_string(n.id), p + cv::Point2d(7, -5), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                  cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
}

void drawCaption(cv::Mat& screen, const std::string& text) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, &baseline);
  cv::rectangle(screen, cv::Rect(6, 6, size.width + 12, size.height + baseline + 10), cv::Scalar(255, 255, 255),
                cv::FILLED);
  cv::putText(screen, text, cv::Point(12, 11 + size.height), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
}

}  // namespace gridtopo::session
