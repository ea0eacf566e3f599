// gridtopo-topology's run of one map file (topology/topology_map_run.h): two rooms joined by a door, labelled with
// the shipped model.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "common/same_outputs.h"
#include "common/scratch.h"
#include "gridtopo/core/error.h"
#include "gridtopo/topology/topology_map_run.h"

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
