// Scale (issue 35, item 3): the whole topology (places::labelPlaces + topology::buildTopology, through
// topology::topologyOfMap) on a synthetic 4000 x 4000 map (200 m x 200 m at 5 cm) of rooms along corridors runs in
// the suite's time with bounded memory: the scans, features and classification go a stripe of the lattice at a
// time, the relaxation keeps a ring of integral rows, the edge routes no step-cost images. This binary runs this
// test alone, so the process's peak resident memory is the pipeline's.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cstdlib>
#include <opencv2/imgcodecs.hpp>

#include "gridtopo/core/process_memory.h"
#include "gridtopo/places/model.h"
#include "gridtopo/topology/pipeline.h"

using namespace gridtopo;

namespace {
// A building filling the image: corridors 2 m wide every 50 m both ways (4 x 4 blocks), and along the top side of
// every block a row of 5 m x 4 m offices, each with a 1 m door onto the corridor; the rest of each block is solid
// (about a tenth of the map is free, like a large SLAM map's bounding box). 255 free, 0 wall.
cv::Mat building(int size_px, double res) {
  cv::Mat img(size_px, size_px, CV_8U, cv::Scalar(0));
  auto m = [&](double metres) { return static_cast<int>(std::lround(metres / res)); };
  const int pitch = m(50), corridor = m(2), wall = m(0.2), span = size_px - 2 * m(1);
  const int blocks = size_px / pitch;
  for (int k = 0; k < blocks; ++k) {
    img(cv::Rect(m(1), k * pitch + m(1), span, corridor)).setTo(255);
    img(cv::Rect(k * pitch + m(1), m(1), corridor, span)).setTo(255);
  }
  for (int by = 0; by < blocks; ++by)
    for (int bx = 0; bx < blocks; ++bx) {
      const int x0 = bx * pitch + m(1) + corridor + wall, y0 = by * pitch + m(1) + corridor + wall;
      for (int x = x0; x + m(5) <= (bx + 1) * pitch + m(1) - wall; x += m(5) + wall) {
        img(cv::Rect(x, y0, m(5), m(4))).setTo(255);
        img(cv::Rect(x + m(2), y0 - wall, m(1), wall)).setTo(255);
      }
    }
  return img;
}
}  // namespace

TEST(TopologyScale, FourThousandSquareMapInBoundedMemory) {
  const ProcessMemory before = processMemory();
  MapImage map;
  map.resolution = 0.05;
  map.grey = building(4000, map.resolution);
  map.source = "<synthetic 4000 x 4000>";
  const places::PlacesModel model =
      places::PlacesModel::load(std::string(GRIDTOPO_DATA_DIR) + "/models/places_model.yml");
  topology::TopologyOptions o;
  o.threads = 2;
  const auto t0 = std::chrono::steady_clock::now();
  const topology::MapTopology run = topology::topologyOfMap(map, model, o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const ProcessMemory after = processMemory();
  const double peak_growth_mb = (static_cast<double>(after.peak_kb) - static_cast<double>(before.rss_kb)) / 1024.0;
  const std::size_t free_cells = static_cast<std::size_t>(cv::countNonZero(map.grey));
  if (const char* dump = std::getenv("GRIDTOPO_SCALE_MAP_PNG")) cv::imwrite(dump, map.grey);  // for profiling
  RecordProperty("seconds", std::to_string(seconds));
  RecordProperty("peak_growth_mb", std::to_string(peak_growth_mb));
  std::cout << "4000 x 4000 map: " << free_cells << " free cells, " << run.labelling.lattice.samples.size()
            << " classified, " << run.topo.graph.nodes.size() << " nodes; " << seconds << " s, peak RSS growth "
            << peak_growth_mb << " MB\n";
  // The map is what it should be: a large free area, many places, a graph of hundreds of nodes.
  EXPECT_GT(free_cells, 1'500'000u);
  EXPECT_GT(run.labelling.lattice.samples.size(), 400'000u);
  EXPECT_GT(run.topo.graph.nodes.size(), 150u);
  EXPECT_GT(run.topo.graph.edges.size(), run.topo.graph.nodes.size());
  // Bounded memory: the pipeline's peak grows the process by 704 MB; before the stripes, the ring of integral rows
  // and the released region images it grew it by 968 MB (the whole map's scans twice and its features at once).
  EXPECT_LT(peak_growth_mb, 800.0);
}
