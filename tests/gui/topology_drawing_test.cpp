// How a topology result is drawn (session::topologyImage, drawTopologyGraph, drawCaption), on the two-room floor plan
// with the hand-made model: the pixels of the labelled map, the graph's nodes at their anchors, the caption's box.
#include <gtest/gtest.h>

#include "gridtopo/session/topology_drawing.h"
#include "test_helpers.h"

using namespace gridtopo;

namespace {

/// Pixels where two BGR images of the same size differ.
int differing(const cv::Mat& a, const cv::Mat& b) {
  int n = 0;
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x) n += a.at<cv::Vec3b>(y, x) != b.at<cv::Vec3b>(y, x);
  return n;
}

const session::TopologyData& planTopology() {
  static const session::TopologyData t = [] {
    session::MapLayer map;
    map.grey = guitest::floorPlan();
    map.resolution = 0.05;
    map.source = "plan";
    return session::computeTopology(map, std::make_shared<places::PlacesModel>(guitest::handMadeModel()),
                                    topology::TopologyOptions());
  }();
  return t;
}

}  // namespace

TEST(TopologyDrawing, LabelledMapBlendsTheLabelColoursOnFreeCellsOnly) {
  const auto& t = planTopology();
  const cv::Mat grey_bgr = session::greyToBgr(t.map.grey);
  // Without labels: the grey map.
  EXPECT_EQ(differing(session::topologyImage(t, session::LabelStage::Corrected, false), grey_bgr), 0);
  const cv::Mat img = session::topologyImage(t, session::LabelStage::Corrected, true);
  ASSERT_EQ(img.size(), t.map.grey.size());
  const cv::Mat& labels = t.labels(session::LabelStage::Corrected);
  int labelled = 0, room = 0, corridor = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c), g = grey_bgr.at<cv::Vec3b>(r, c);
      const unsigned char l = labels.at<unsigned char>(r, c);
      if (l > 2) {
        ASSERT_EQ(p, g) << "unlabelled cell (" << r << ", " << c << ") changed";
        continue;
      }
      ++labelled;
      // Blended with alpha 0.25 + 0.5 · p(label) in [0.25, 0.75] towards the label's colour, from white (free).
      const cv::Scalar col = session::labelColour(l);
      for (int k = 0; k < 3; ++k) {
        const double lo = std::min(0.25 * col[k] + 0.75 * g[k], 0.75 * col[k] + 0.25 * g[k]);
        const double hi = std::max(0.25 * col[k] + 0.75 * g[k], 0.75 * col[k] + 0.25 * g[k]);
        ASSERT_GE(p[k] + 0.5, lo);
        ASSERT_LE(p[k] - 0.5, hi);
      }
      room += l == 0;
      corridor += l == 1;
    }
  std::printf("plan: %d labelled cells, %d room, %d corridor\n", labelled, room, corridor);
  EXPECT_GT(room, 6000);      // two 4 m x 3 m rooms: 2 x 80 x 60 cells
  EXPECT_GT(corridor, 2500);  // 9 m x 1.2 m
  // A loaded result (no labelling kept) blends with the fixed alpha 0.6.
  session::TopologyData loaded = t;
  loaded.has_labelling = false;
  const cv::Mat fixed = session::topologyImage(loaded, session::LabelStage::Corrected, true);
  const cv::Vec3b p = fixed.at<cv::Vec3b>(30, 30);
  ASSERT_EQ(labels.at<unsigned char>(30, 30), 0);
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(p[k], static_cast<int>(std::lround(0.4 * 255 + 0.6 * session::labelColour(0)[k])));
}

TEST(TopologyDrawing, GraphNodesSitAtTheirAnchorsInTheirLabelsColour) {
  const auto& t = planTopology();
  ASSERT_GE(t.topo.graph.nodes.size(), 3u);  // two rooms and the corridor (and the doors)
  session::ViewTransform v;
  v.fit(t.map.origin_x, t.map.origin_y, t.map.origin_x + t.map.width_m(), t.map.origin_y + t.map.height_m(), 800,
        480);
  const cv::Mat blank(480, 800, CV_8UC3, cv::Scalar(72, 72, 72));
  cv::Mat screen = blank.clone();
  session::drawTopologyGraph(screen, v, t, false, false);
  EXPECT_EQ(differing(screen, blank), 0);  // nothing asked for, nothing drawn
  session::drawTopologyGraph(screen, v, t, true, false);
  int dark = 0;
  for (int y = 0; y < screen.rows; ++y)
    for (int x = 0; x < screen.cols; ++x) dark += screen.at<cv::Vec3b>(y, x) == cv::Vec3b(20, 20, 20);
  EXPECT_GT(dark, 50);  // the edges
  for (const auto& n : t.topo.graph.nodes) {
    const cv::Point2d w = session::nodeAnchorWorld(t, n);
    const cv::Point2d s = v.toScreen(w.x, w.y);
    const cv::Vec3b p = screen.at<cv::Vec3b>(static_cast<int>(std::lround(s.y)), static_cast<int>(std::lround(s.x)));
    const cv::Scalar c = session::labelColour(n.label);
    EXPECT_EQ(p, cv::Vec3b(c[0], c[1], c[2])) << "node " << n.id;
  }
  // Region ids: anti-aliased black text beside each node, nothing else.
  cv::Mat ids = blank.clone();
  session::drawTopologyGraph(ids, v, t, false, true);
  int text = 0, other = 0;
  for (int y = 0; y < ids.rows; ++y)
    for (int x = 0; x < ids.cols; ++x) {
      const cv::Vec3b p = ids.at<cv::Vec3b>(y, x);
      text += p[0] < 40 && p[0] == p[1] && p[1] == p[2];
      other += p != cv::Vec3b(72, 72, 72) && !(p[0] < 72 && p[0] == p[1] && p[1] == p[2]);
    }
  EXPECT_GT(text, static_cast<int>(t.topo.graph.nodes.size()) * 5);
  EXPECT_EQ(other, 0);
}

TEST(TopologyDrawing, CaptionIsAWhiteBoxAtTheTopLeft) {
  const cv::Mat blank(200, 600, CV_8UC3, cv::Scalar(72, 72, 72));
  cv::Mat screen = blank.clone();
  session::drawCaption(screen, "topology of scan 12 (3 updates): 2 regions, 1 edges");
  EXPECT_EQ(screen.at<cv::Vec3b>(8, 8), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(screen.at<cv::Vec3b>(100, 300), cv::Vec3b(72, 72, 72));  // below the box: untouched
  int dark = 0, changed = 0;
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < screen.cols; ++x) {
      dark += screen.at<cv::Vec3b>(y, x)[0] < 128;
      changed += screen.at<cv::Vec3b>(y, x) != blank.at<cv::Vec3b>(y, x);
    }
  EXPECT_GT(dark, 300);  // the text, black on white
  EXPECT_GT(changed, 300 * 20);
  EXPECT_EQ(differing(screen.rowRange(60, 200), blank.rowRange(60, 200)), 0);
}
