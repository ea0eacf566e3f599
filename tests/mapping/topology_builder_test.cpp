#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/slam/CMetricMapBuilderICP.h>

#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "common/rawlog_feed.h"
#include "common/run_app.h"
#include "gridtopo/core/error.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/io/scan_conversion.h"
#include "gridtopo/mapping/topology_builder.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/mapping/rbpf_map_builder.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {

const sim::SimLog& officeLog() {
  static const sim::SimLog log = sim::simulate(sim::FloorPlan::officeLoop(), sim::officeLoopWaypoints(1), {});
  return log;
}

std::shared_ptr<const places::PlacesModel> model() {
  static const auto m = std::make_shared<const places::PlacesModel>(
      places::PlacesModel::load(std::string(GRIDTOPO_DATA_DIR) + "/models/places_model.yml"));
  return m;
}

std::shared_ptr<mapping::CMetricMapBuilderGridRbpf> ourSlam() {
  slam::SlamOptions o;
  o.particles = 10;
  o.threads = 2;
  return std::make_shared<mapping::CMetricMapBuilderGridRbpf>(o);
}

std::array<int, 3> nodeCounts(const topology::TopologicalGraph& g) {
  std::array<int, 3> c{0, 0, 0};
  for (const auto& n : g.nodes) c[n.label]++;
  return c;
}

}  // namespace

TEST(TopologyBuilder, RecomputesOnScheduleAndLabelsTheOffice) {
  mapping::TopologyBuilderOptions schedule;
  schedule.update_every = 40;
  mapping::CMetricMapBuilderTopology builder(model(), topology::TopologyOptions(), schedule, ourSlam());
  std::vector<unsigned> update_sizes;
  builder.onTopologyUpdated = [&](const mapping::MapTopology& t) { update_sizes.push_back(t.map_size); };
  testing_feed::feedActionObservation(builder, officeLog().records);

  // Every 40 processed scans, at exactly the multiples of 40 (each processed scan grows the map by one).
  const unsigned size = builder.getCurrentlyBuiltMapSize();
  std::printf("office: %zu scans, %u processed, %zu updates\n", officeLog().records.size(), size,
              update_sizes.size());
  ASSERT_GE(size, 200u);
  const std::size_t expected_updates = size / 40;
  ASSERT_EQ(update_sizes.size(), expected_updates);
  for (std::size_t i = 0; i < update_sizes.size(); ++i) EXPECT_EQ(update_sizes[i], 40 * (i + 1));
  EXPECT_EQ(builder.topologyUpdates(), update_sizes.size());

  // On request: the final map.
  const std::size_t scheduled = update_sizes.size();
  builder.updateTopology();
  const auto t = builder.currentTopology();
  ASSERT_TRUE(t);
  EXPECT_EQ(t->map_size, size);
  EXPECT_EQ(builder.topologyUpdates(), scheduled + 1);
  EXPECT_EQ(update_sizes.back(), size);

  // Free cells have place labels (all but those of lattice blocks without a sample), and only free cells.
  std::size_t free = 0, labelled = 0, labelled_not_free = 0;
  for (int r = 0; r < t->occ.rows(); ++r)
    for (int c = 0; c < t->occ.cols(); ++c) {
      const bool is_free = t->occ.isFree(r, c);
      const bool has_label = t->labels().at<unsigned char>(r, c) != places::kNoLabel;
      free += is_free;
      labelled += has_label && is_free;
      labelled_not_free += has_label && !is_free;
    }
  std::printf("office: %zu free cells, %zu labelled\n", free, labelled);
  EXPECT_EQ(labelled_not_free, 0u);
  // The office is 20 m x 12 m: well over 40 m2 of seen free floor at 5 cm cells.
  EXPECT_GT(free, 16000u);
  EXPECT_GT(labelled, free * 98 / 100);
  const auto counts = nodeCounts(t->graph());
  std::printf("office topology: %zu free cells, %d rooms, %d corridors, %d doorways, %zu edges\n", free, counts[0],
              counts[1], counts[2], t->graph().edges.size());
  // The office: a corridor loop around a block of rooms. Measured: 4 rooms, 3 corridor pieces, 7 doorways, 21 edges;
  // of the labelled cells 41 % room, 55 % corridor.
  std::array<std::size_t, 3> cells{0, 0, 0};
  for (int r = 0; r < t->labels().rows; ++r)
    for (int c = 0; c < t->labels().cols; ++c)
      if (const auto l = t->labels().at<unsigned char>(r, c); l < 3) cells[l]++;
  std::printf("office cells: room %zu, corridor %zu, doorway %zu\n", cells[0], cells[1], cells[2]);
  EXPECT_GE(counts[0], 3);  // rooms
  EXPECT_GE(counts[1], 2);  // corridor pieces
  EXPECT_GE(counts[2], 3);  // doorways
  EXPECT_GT(cells[0], labelled / 10);
  EXPECT_GT(cells[1], labelled / 4);
  EXPECT_GE(t->graph().edges.size(), 1u);
  EXPECT_EQ(t->graph().connectedComponents(), 1);

  // The same labels, regions and graph as gridtopo-topology on the final map written as gridtopo-slam writes it.
  const fs::path dir = fs::temp_directory_path() / ("gridtopo_topology_builder_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto* grid = builder.getCurrentlyBuiltMetricMap()->mapByClass<mrpt::maps::COccupancyGridMap2D>().get();
  ASSERT_NE(grid, nullptr);
  io::writeGridmapGz(*grid, (dir / "map.gridmap.gz").string());
  // With the path the builder gave the map preparation: its metric builder's simple map's poses.
  mrpt::maps::CSimpleMap sm;
  builder.getCurrentlyBuiltMap(sm);
  std::vector<TimedPose> path;
  for (const cv::Point2d& p : mapping::pathOfSimpleMap(sm)) path.push_back({0.0, {p.x, p.y, 0.0}});
  io::writeTrajectory((dir / "path.txt").string(), path);
  const auto run = testing_app::runApp("gridtopo-topology", (dir / "map.gridmap.gz").string() + " -t " +
                                                                (dir / "path.txt").string() + " -q -m " +
                                                                GRIDTOPO_DATA_DIR "/models/places_model.yml -o " +
                                                                (dir / "topo").string());
  ASSERT_EQ(run.status, 0) << run.output;
  const cv::Mat app_labels = places::labelsFromCodes(cv::imread((dir / "topo/labels.png").string(), cv::IMREAD_GRAYSCALE));
  ASSERT_EQ(app_labels.size(), t->labels().size());
  EXPECT_EQ(cv::countNonZero(app_labels != t->labels()), 0);
  const cv::Mat app_before =
      places::labelsFromCodes(cv::imread((dir / "topo/labels_before_correction.png").string(), cv::IMREAD_GRAYSCALE));
  EXPECT_EQ(cv::countNonZero(app_before != t->labelling.labels), 0);
  std::ifstream json((dir / "topo/topology.json").string());
  const std::string app_json((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  EXPECT_EQ(app_json, topology::toJson(t->graph()));
  fs::remove_all(dir);
}

TEST(TopologyBuilder, OnRequestOnlyAndForwardsTheMetricBuilder) {
  auto slam = ourSlam();
  mapping::CMetricMapBuilderTopology builder(model(), topology::TopologyOptions(), {}, slam);
  // The observation-only layout: odometry, then the scan.
  const auto& log = officeLog();
  for (std::size_t i = 0; i < 150; ++i) {
    auto odo = mrpt::obs::CObservationOdometry::Create();
    odo->odometry = mrpt::poses::CPose2D(log.records[i].odometry);
    builder.processObservation(odo);
    builder.processObservation(io::toMrptScan(log.records[i].scan));
  }
  EXPECT_EQ(builder.topologyUpdates(), 0u);  // update_every = 0: on request only
  EXPECT_FALSE(builder.currentTopology());
  // The wrapped builder got every scan and answers through the wrapper.
  EXPECT_GT(slam->filter().stepsProcessed(), 20u);
  EXPECT_EQ(builder.getCurrentlyBuiltMapSize(), slam->filter().stepsProcessed());
  mrpt::maps::CSimpleMap sm;
  builder.getCurrentlyBuiltMap(sm);
  EXPECT_EQ(sm.size(), slam->filter().stepsProcessed());
  EXPECT_EQ(builder.getCurrentlyBuiltMetricMap(), slam->getCurrentlyBuiltMetricMap());
  EXPECT_EQ(builder.getCurrentPoseEstimation()->getMeanVal(), slam->getCurrentPoseEstimation()->getMeanVal());
  builder.updateTopology();
  ASSERT_TRUE(builder.currentTopology());
  EXPECT_EQ(builder.topologyUpdates(), 1u);
  EXPECT_GT(places::countFree(builder.currentTopology()->occ), 1000u);

  // enableMapUpdating reaches the wrapped builder; initialize() restarts it and forgets the topology.
  builder.options.enableMapUpdating = false;
  const auto steps = slam->filter().stepsProcessed();
  builder.processObservation(io::toMrptScan(log.records[150].scan));
  EXPECT_EQ(slam->run().scansFed(), 150u);
  EXPECT_EQ(slam->filter().stepsProcessed(), steps);
  builder.initialize();
  EXPECT_EQ(builder.getCurrentlyBuiltMapSize(), 0u);
  EXPECT_FALSE(builder.currentTopology());
  EXPECT_EQ(builder.topologyUpdates(), 0u);
}

TEST(TopologyBuilder, WrapsAnotherMrptBuilder) {
  // MRPT's ICP-SLAM with an occupancy grid among its maps: any CMetricMapBuilder is accepted.
  auto icp = std::make_shared<mrpt::slam::CMetricMapBuilderICP>();
  icp->setVerbosityLevel(mrpt::system::LVL_ERROR);
  icp->ICP_options.mapInitializers.clear();
  icp->ICP_options.mapInitializers.push_back(mrpt::maps::CSimplePointsMap::TMapDefinition());
  mrpt::maps::COccupancyGridMap2D::TMapDefinition grid_def;
  grid_def.resolution = 0.05f;
  icp->ICP_options.mapInitializers.push_back(grid_def);
  icp->initialize();
  mapping::TopologyBuilderOptions schedule;
  schedule.update_every = 1000;
  mapping::CMetricMapBuilderTopology builder(model(), topology::TopologyOptions(), schedule, icp);
  const auto& log = officeLog();
  for (std::size_t i = 0; i < 120; ++i) {
    auto odo = mrpt::obs::CObservationOdometry::Create();
    odo->odometry = mrpt::poses::CPose2D(log.records[i].odometry);
    builder.processObservation(odo);
    builder.processObservation(io::toMrptScan(log.records[i].scan));
  }
  EXPECT_GT(builder.getCurrentlyBuiltMapSize(), 5u);
  builder.updateTopology();
  const auto t = builder.currentTopology();
  ASSERT_TRUE(t);
  std::printf("ICP: %u frames, %zu free cells, %zu nodes\n", t->map_size, places::countFree(t->occ),
              t->graph().nodes.size());
  EXPECT_GT(places::countFree(t->occ), 1000u);
  EXPECT_GE(t->graph().nodes.size(), 1u);

  // A metric map without an occupancy grid is bad input, named.
  auto points_only = std::make_shared<mrpt::slam::CMetricMapBuilderICP>();
  points_only->setVerbosityLevel(mrpt::system::LVL_ERROR);
  points_only->ICP_options.mapInitializers.clear();
  points_only->ICP_options.mapInitializers.push_back(mrpt::maps::CSimplePointsMap::TMapDefinition());
  points_only->initialize();
  mapping::CMetricMapBuilderTopology no_grid(model(), topology::TopologyOptions(), {}, points_only);
  try {
    no_grid.updateTopology();
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no occupancy grid"), std::string::npos) << e.what();
  }
}

TEST(TopologyBuilderOptions, LoadSaveAndBadValues) {
  mrpt::config::CConfigFileMemory ini;
  ini.write("topology_builder", "update_every", 25);
  mapping::TopologyBuilderOptions o;
  o.loadFromConfigFile(ini, "topology_builder");
  EXPECT_EQ(o.update_every, 25u);
  mrpt::config::CConfigFileMemory saved;
  o.saveToConfigFile(saved, "topology_builder");
  mapping::TopologyBuilderOptions back;
  back.loadFromConfigFile(saved, "topology_builder");
  EXPECT_EQ(back.update_every, 25u);
  EXPECT_EQ(mapping::topologyBuilderOptionKeys(), std::vector<std::string>{"update_every"});
  for (const char* bad : {"-3", "2.5", "often"}) {
    mrpt::config::CConfigFileMemory b;
    b.write("topology_builder", "update_every", std::string(bad));
    mapping::TopologyBuilderOptions x;
    try {
      x.loadFromConfigFile(b, "topology_builder");
      FAIL() << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "[topology_builder] update_every") << e.what();
    }
  }
}
