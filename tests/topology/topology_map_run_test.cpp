// gridtopo-topology's run of one map file (topology/topology_map_run.h): two rooms joined by a door, labelled with
// the shipped model.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "common/same_outputs.h"
#include "common/scratch.h"
#include "gridtopo/core/error.h"
#include "gridtopo/places/model.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/topology/topology_map_run.h"
#include "gridtopo/topology/topology_outputs.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
/// Two 4 m x 3 m rooms side by side at 5 cm per pixel, a 0.9 m door in the wall between them; 254 free, 0 wall.
std::string twoRooms(const fs::path& dir) {
  cv::Mat img(70, 170, CV_8U, cv::Scalar(0));
  img(cv::Rect(5, 5, 80, 60)).setTo(254);
  img(cv::Rect(87, 5, 78, 60)).setTo(254);
  img(cv::Rect(85, 26, 2, 18)).setTo(254);
  const std::string path = (dir / "rooms.png").string();
  cv::imwrite(path, img);
  return path;
}
}  // namespace

TEST(TopologyMapRun, LabelsTheMapAndWritesTheOutputSetWithTheRunsIni) {
  const fs::path dir = test::scratch("map_run");
  topology::TopologyRunSpec spec;
  spec.map = twoRooms(dir);
  spec.model = std::string(GRIDTOPO_DATA_DIR) + "/models/places_model.yml";
  spec.output = (dir / "out").string();
  spec.options.resolution = 0.05;
  std::ostringstream log;
  topology::runTopologyOnMapFile(spec, true, log);
  for (const char* f : {"topology.graphml", "topology.json", "labels.png", "segmentation.png", "overlay.png"})
    EXPECT_TRUE(fs::exists(fs::path(spec.output) / f)) << f;
  EXPECT_EQ(testing_outputs::slurp(fs::path(spec.output) / "options.ini"), topology::topologyRunIni(spec));
  const cv::Mat labels = cv::imread((fs::path(spec.output) / "labels.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(labels.size(), cv::Size(170, 70));   // pixel-aligned with the map
  EXPECT_EQ(labels.at<unsigned char>(35, 40), 77);  // the middle of the left room is a room
  // The summary names the map.
  EXPECT_NE(log.str().find(spec.map + ": 170x70 cells"), std::string::npos) << log.str();
}

TEST(TopologyMapRun, AMissingModelIsBadInputAndWritesNothing) {
  const fs::path dir = test::scratch("map_run_bad");
  topology::TopologyRunSpec spec;
  spec.map = twoRooms(dir);
  spec.model = (dir / "nowhere.yml").string();
  spec.output = (dir / "out").string();
  std::ostringstream log;
  EXPECT_THROW(topology::runTopologyOnMapFile(spec, true, log), InputError);
  EXPECT_FALSE(fs::exists(spec.output));
}

// gridtopo-topology's run (topologyOfMap with outputs_only: the box of the places, the labels and the occupancy as
// runs, the region borders instead of the ids, the segmentation in 16 bits, no lattice grids) writes the very files
// of the whole-map run the GUI makes, on a SLAM-like map whose building fills a part of it, with a path.
TEST(TopologyMapRun, OutputsOnlyWritesTheFilesOfTheWholeRun) {
  MapImage map;
  map.resolution = 0.05;
  map.kind = MapKind::ProbabilisticGrid;
  map.source = "<building in the unknown>";
  map.grey = cv::Mat(300, 420, CV_8U, cv::Scalar(127));  // unknown
  const cv::Rect b(131, 77, 176, 130);                       // the building: walls, two rooms, a corridor, doors
  map.grey(b).setTo(0);
  map.grey(cv::Rect(b.x + 3, b.y + 3, 80, 70)).setTo(255);
  map.grey(cv::Rect(b.x + 86, b.y + 3, 87, 70)).setTo(255);
  map.grey(cv::Rect(b.x + 3, b.y + 76, 170, 30)).setTo(255);   // corridor
  map.grey(cv::Rect(b.x + 30, b.y + 73, 18, 3)).setTo(255);    // doors onto it
  map.grey(cv::Rect(b.x + 120, b.y + 73, 18, 3)).setTo(255);
  map.grey(cv::Rect(b.x + 60, b.y + 30, 8, 8)).setTo(0);       // furniture
  // The path (world metres, y up): along the corridor, into each room and back.
  const auto world = [&](double col, double row) { return cv::Point2d(col * 0.05, (map.grey.rows - row) * 0.05); };
  for (double c = b.x + 10; c <= b.x + 165; c += 2) map.path.push_back(world(c, b.y + 90));
  for (double r = b.y + 90; r >= b.y + 30; r -= 2) map.path.push_back(world(b.x + 128, r));
  for (double r = b.y + 30; r <= b.y + 90; r += 2) map.path.push_back(world(b.x + 128, r));
  for (double c = b.x + 165; c >= b.x + 39; c -= 2) map.path.push_back(world(c, b.y + 90));
  for (double r = b.y + 90; r >= b.y + 30; r -= 2) map.path.push_back(world(b.x + 39, r));
  const places::PlacesModel model =
      places::PlacesModel::load(std::string(GRIDTOPO_DATA_DIR) + "/models/places_model.yml");
  const topology::TopologyOptions o;
  const topology::MapTopology whole = topology::topologyOfMap(map, model, o);
  const topology::MapTopology part = topology::topologyOfMap(map, model, o, {}, false, /*outputs_only=*/true);
  EXPECT_LT(part.topo.frame.area() * 3, whole.topo.frame.area());  // the box, not the map
  EXPECT_TRUE(part.labelling.labels.empty() && part.topo.regions.ids.empty() && part.labelling.probs.empty());
  EXPECT_EQ(part.topo.segmentation.type(), CV_16U);
  ASSERT_GE(whole.topo.graph.nodes.size(), 3u);
  const fs::path dir = test::scratch("map_run_outputs_only");
  topology::writeTopologyOutputs((dir / "whole").string(), whole.occ, whole.topo, whole.labelling.labels, 2, "ini\n");
  topology::writeTopologyOutputs((dir / "part").string(), part.occ, part.topo, part.labelling.labels, 2, "ini\n");
  std::size_t files = 0;
  for (const auto& f : fs::directory_iterator(dir / "whole")) {
    ++files;
    EXPECT_EQ(testing_outputs::slurp(f.path()), testing_outputs::slurp(dir / "part" / f.path().filename()))
        << f.path().filename();
  }
  EXPECT_EQ(files, 10u);  // graphml, json, dot, pose graph, overlay, labels, labels before correction, two segmentations, ini
}
