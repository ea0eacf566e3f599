#include <gtest/gtest.h>

#include "common/scratch.h"

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "gridtopo/places/labelling.h"
#include "gridtopo/places/occupancy.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/topology_outputs.h"

using namespace gridtopo;
using namespace gridtopo::topology;
namespace fs = std::filesystem;

namespace {
// Two 3 m x 3 m rooms joined by a 1 m doorway, at 0.05 m per cell.
struct TwoRooms {
  places::OccupancyImage occ;
  cv::Mat labels;
  TwoRooms() {
    occ.resolution = 0.05;
    occ.cells = cv::Mat(80, 150, CV_8U, cv::Scalar(places::kOccupied));
    labels = cv::Mat(80, 150, CV_8U, cv::Scalar(places::kNoLabel));
    labels(cv::Rect(10, 10, 60, 60)).setTo(static_cast<int>(places::PlaceLabel::Room));
    labels(cv::Rect(80, 10, 60, 60)).setTo(static_cast<int>(places::PlaceLabel::Room));
    labels(cv::Rect(70, 30, 10, 20)).setTo(static_cast<int>(places::PlaceLabel::Doorway));
    occ.cells.setTo(places::kFree, labels != places::kNoLabel);
  }
};
std::string slurp(const fs::path& p) {
  std::ostringstream s;
  s << std::ifstream(p).rdbuf();
  return s.str();
}
}  // namespace

TEST(TopologyOutputs, WritesTheWholeSet) {
  const TwoRooms m;
  const TopologyResult topo = buildTopology(m.labels, m.occ.resolution, TopologyOptions{});
  ASSERT_EQ(topo.graph.nodes.size(), 3u);  // room, doorway, room
  const fs::path dir = gridtopo::test::scratchPath("topology_outputs_test");
  fs::remove_all(dir);
  writeTopologyOutputs(dir.string(), m.occ, topo, m.labels, 2, "[topology]\nthreads = 2\n");
  for (const char* f : {"topology.graphml", "topology.json", "topology.dot", "topology_posegraph.graph", "overlay.png",
                        "labels.png", "labels_before_correction.png", "segmentation.png", "segmentation_colour.png",
                        "options.ini"})
    EXPECT_TRUE(fs::is_regular_file(dir / f)) << f;
  EXPECT_EQ(slurp(dir / "options.ini"), "[topology]\nthreads = 2\n");
  EXPECT_EQ(slurp(dir / "topology.json"), toJson(topo.graph));
  const cv::Mat codes = cv::imread((dir / "labels.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(cv::countNonZero(codes != places::labelsToCodes(topo.labels)), 0);
  EXPECT_EQ(cv::imread((dir / "overlay.png").string()).cols, 2 * m.labels.cols);  // overlay_scale 2
  const cv::Mat seg = cv::imread((dir / "segmentation.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(seg.type(), CV_16U);
  fs::remove_all(dir);
}

// The GUI's save without a labelling or a segmentation leaves those pictures out.
TEST(TopologyOutputs, LeavesOutWhatTheRunDoesNotHave) {
  const TwoRooms m;
  TopologyResult topo = buildTopology(m.labels, m.occ.resolution, TopologyOptions{});
  topo.segmentation.release();
  const fs::path dir = gridtopo::test::scratchPath("topology_outputs_test_partial");
  fs::remove_all(dir);
  writeTopologyOutputs(dir.string(), m.occ, topo, cv::Mat(), 1, "");
  EXPECT_TRUE(fs::is_regular_file(dir / "labels.png"));
  EXPECT_FALSE(fs::exists(dir / "labels_before_correction.png"));
  EXPECT_FALSE(fs::exists(dir / "segmentation.png"));
  EXPECT_FALSE(fs::exists(dir / "segmentation_colour.png"));
  fs::remove_all(dir);
}

// overlay.png's enlargement stays within ImageMagick's default limits (16 384 px a side, 128 Mpx): the hospital's
// SLAM map (10 079 x 5 034 cells) gets 1 instead of 2; small maps keep what was asked for.
TEST(TopologyOutputs, OverlayScaleStaysWithinCommonImageLimits) {
  EXPECT_EQ(overlayScaleFor({821, 773}, 2), 2);     // Intel
  EXPECT_EQ(overlayScaleFor({821, 773}, 8), 8);     // 6 568 x 6 184 = 40.6 Mpx
  EXPECT_EQ(overlayScaleFor({1030, 1028}, 0), 1);   // at least 1
  EXPECT_EQ(overlayScaleFor({10079, 5034}, 2), 1);  // the hospital: 20 158 px wide at 2
  EXPECT_EQ(overlayScaleFor({8192, 100}, 2), 2);    // 16 384 px: just fits
  EXPECT_EQ(overlayScaleFor({8193, 100}, 2), 1);
  EXPECT_EQ(overlayScaleFor({6000, 6000}, 2), 1);   // 144 Mpx at 2
  EXPECT_EQ(overlayScaleFor({5000, 5000}, 3), 2);   // 225 Mpx at 3, 100 at 2
  EXPECT_EQ(overlayScaleFor({20000, 20000}, 2), 1);  // larger than the limits even at 1: 1
}
