// The live topology of a SLAM run (session::LiveTopology over session::SlamRunner) on a simulated office log: results
// for increasing scan counts, the last one exactly the topology builder's on the final map, the same result for a
// scan count whatever the timing, the SLAM unchanged, and a clean stop in the middle of a computation.
#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <vector>

#include "common/same_outputs.h"
#include "gridtopo/mapping/topology_builder.h"
#include "gridtopo/session/live_topology.h"
#include "gridtopo/session/session.h"
#include "gridtopo/session/slam_runner.h"
#include "gridtopo/session/topology_drawing.h"
#include "gridtopo/slam/slam_run.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/map_export.h"

using namespace gridtopo;
using namespace std::chrono_literals;

namespace {

std::shared_ptr<const std::vector<ScanRecord>> officeScans() {
  static const auto s = std::make_shared<const std::vector<ScanRecord>>(
      sim::simulate(sim::FloorPlan::officeLoop(), sim::officeLoopWaypoints(1), {}).records);
  return s;
}

std::shared_ptr<const places::PlacesModel> shippedModel() {
  static const auto m = std::make_shared<const places::PlacesModel>(
      places::PlacesModel::load(std::string(GRIDTOPO_DATA_DIR) + "/models/places_model.yml"));
  return m;
}

slam::SlamOptions slamOptions() {
  slam::SlamOptions o;
  o.particles = 8;
  o.seed = 7;
  o.threads = 1;
  return o;
}

topology::TopologyOptions topologyOptions() {
  topology::TopologyOptions o;
  o.threads = 1;
  return o;
}

/// Pixels where two label images differ (both must have the same size).
int differingCells(const cv::Mat& a, const cv::Mat& b) {
  EXPECT_EQ(a.size(), b.size());
  if (a.size() != b.size()) return -1;
  return cv::countNonZero(a != b);
}

/// Pixels of `roi` where two BGR images differ.
int differingPixels(const cv::Mat& a, const cv::Mat& b, const cv::Rect& roi) {
  int n = 0;
  for (int y = roi.y; y < roi.y + roi.height; ++y)
    for (int x = roi.x; x < roi.x + roi.width; ++x) n += a.at<cv::Vec3b>(y, x) != b.at<cv::Vec3b>(y, x);
  return n;
}

struct Collected {
  std::mutex mu;
  std::vector<std::shared_ptr<const session::LiveTopologyResult>> results;
  std::function<void(std::shared_ptr<const session::LiveTopologyResult>)> sink() {
    return [this](std::shared_ptr<const session::LiveTopologyResult> r) {
      std::lock_guard<std::mutex> lk(mu);
      results.push_back(std::move(r));
    };
  }
};

constexpr std::size_t kEvery = 40;

}  // namespace

TEST(LiveTopology, FollowsTheRunAndEndsWithTheBuildersTopologyOfTheFinalMap) {
  Collected got;
  session::SlamRunner runner(officeScans(), slamOptions());
  session::LiveTopology live(shippedModel(), topologyOptions(), got.sink());
  runner.setBestMapListener(kEvery, live.listener());
  runner.play();
  ASSERT_TRUE(runner.waitIdle(600s));
  ASSERT_TRUE(live.waitIdle(600s));
  const auto snap = runner.snapshot();
  ASSERT_EQ(snap->state, session::RunState::Finished);
  const std::size_t final_steps = snap->steps;
  std::printf("office: %zu scans, %zu updates; live topology: %zu requests, %zu dropped, %zu computed\n",
              snap->scans_fed, final_steps, live.requests(), live.dropped(), live.computed());
  ASSERT_GE(final_steps, 200u);

  // One request per multiple of kEvery plus the end; results for strictly increasing scan counts, every one a
  // multiple of kEvery or the end, with the scans fed at that update.
  EXPECT_EQ(live.requests(), final_steps / kEvery + (final_steps % kEvery ? 1 : 0));
  EXPECT_EQ(live.computed() + live.dropped(), live.requests());
  ASSERT_GE(got.results.size(), 2u);
  for (std::size_t i = 0; i < got.results.size(); ++i) {
    const auto& r = *got.results[i];
    EXPECT_EQ(r.sequence, i + 1);
    if (i > 0) {
      EXPECT_GT(r.steps, got.results[i - 1]->steps);
    }
    EXPECT_TRUE(r.steps % kEvery == 0 || r.steps == final_steps) << r.steps;
    ASSERT_LT(r.steps - 1, snap->stats.size());
    // Scheduled: the scan that made the update is the last one fed; at the end, every scan of the log was fed.
    EXPECT_EQ(r.scans_fed, r.steps == final_steps ? snap->scans_fed : snap->stats[r.steps - 1].scan_index + 1);
    ASSERT_TRUE(r.data) << r.error;
    EXPECT_EQ(r.data->map.source, "<slam map, " + std::to_string(r.steps) + " scans>");
  }
  const auto last = live.latest();
  ASSERT_TRUE(last && last->data);
  EXPECT_EQ(last, got.results.back());
  EXPECT_EQ(last->steps, final_steps);
  EXPECT_EQ(last->scans_fed, snap->scans_fed);

  // Exactly what the topology map builder (gridtopo-map) computes from the final best map and every scan's pose.
  const auto grid = slam::toOccupancyGrid(snap->resultMap());  // at the end: the loop closure's map
  std::vector<cv::Point2d> path;
  for (const TimedPose& p : snap->trajectory) path.emplace_back(p.pose.x, p.pose.y);
  const mapping::MapTopology ref =
      mapping::topologyOfSlamGrid(grid, *shippedModel(), topologyOptions(), "final", {}, std::move(path));
  EXPECT_EQ(differingCells(last->data->map.grey, ref.map.grey), 0);
  EXPECT_DOUBLE_EQ(last->data->map.origin_x, ref.map.origin.x);
  EXPECT_DOUBLE_EQ(last->data->map.origin_y, ref.map.origin.y);
  EXPECT_EQ(differingCells(last->data->topo.labels, ref.labels()), 0);
  EXPECT_EQ(differingCells(last->data->labelling.labels, ref.labelling.labels), 0);
  EXPECT_EQ(last->data->topo.graph.nodes.size(), ref.graph().nodes.size());
  EXPECT_EQ(last->data->topo.graph.edges.size(), ref.graph().edges.size());
  // The same trajectory evidence: the door passages and room entries of the run's path.
  EXPECT_EQ(last->data->topo.door_passages.size(), ref.topo.door_passages.size());
  EXPECT_EQ(last->data->topo.room_entries.size(), ref.topo.room_entries.size());
  std::printf("final live topology: %zu door passages, %zu room entries of the path\n",
              last->data->topo.door_passages.size(), last->data->topo.room_entries.size());
  // The office (rooms around a corridor loop); measured with these options: 2 rooms, 2 corridor pieces, 5 doorways,
  // 16 edges (3 rooms, 4 corridor pieces, 18 edges before the map preparation took the fans and frayed edges).
  std::array<int, 3> counts{0, 0, 0};
  for (const auto& n : last->data->topo.graph.nodes) counts[n.label]++;
  std::printf("final live topology: %d rooms, %d corridors, %d doorways, %zu edges, %.2f s\n", counts[0], counts[1],
              counts[2], last->data->topo.graph.edges.size(), last->seconds);
  EXPECT_GE(counts[0], 2);
  EXPECT_GE(counts[1], 1);
  EXPECT_GE(counts[2], 3);
  EXPECT_EQ(session::liveTopologyCaption(*last),
            "topology of scan " + std::to_string(snap->scans_fed) + " (" + std::to_string(final_steps) +
                " updates): " + std::to_string(ref.graph().nodes.size()) + " regions, " +
                std::to_string(ref.graph().edges.size()) + " edges");

  // The same scan count reached another way (stepping, no schedule: the topology of the paused run) gives the same
  // labels: results depend on the scan count, not on the timing.
  const auto& first = *got.results.front();
  session::SlamRunner stepped(officeScans(), slamOptions());
  session::LiveTopology on_pause(shippedModel(), topologyOptions());
  stepped.setBestMapListener(0, on_pause.listener());
  stepped.step(first.steps);
  ASSERT_TRUE(stepped.waitIdle(600s));
  ASSERT_TRUE(on_pause.waitIdle(600s));
  const auto again = on_pause.latest();
  ASSERT_TRUE(again && again->data);
  EXPECT_EQ(on_pause.requests(), 1u);
  EXPECT_EQ(again->steps, first.steps);
  EXPECT_EQ(differingCells(again->data->topo.labels, first.data->topo.labels), 0);
  EXPECT_EQ(again->data->topo.graph.nodes.size(), first.data->topo.graph.nodes.size());
}

TEST(LiveTopology, LeavesTheSlamUnchanged) {
  // The SLAM run alone (filter and loop closure), then a runner with the live topology every 10 updates: the same
  // trajectory, pose by pose.
  slam::SlamRun direct(officeScans(), slamOptions());
  direct.runToEnd();
  session::SlamRunner runner(officeScans(), slamOptions());
  session::LiveTopology live(shippedModel(), topologyOptions());
  runner.setBestMapListener(10, live.listener());
  runner.play();
  ASSERT_TRUE(runner.waitIdle(600s));
  const auto snap = runner.snapshot();
  EXPECT_GE(live.requests(), snap->steps / 10);
  testing_outputs::expectSameTrajectory(snap->trajectory, direct.trajectory());
  ASSERT_TRUE(live.waitIdle(600s));
}

TEST(LiveTopology, DropsIntermediateRequestsAndStopsInTheMiddleOfAComputation) {
  session::SlamRunner runner(officeScans(), slamOptions());
  runner.play();
  ASSERT_TRUE(runner.waitIdle(600s));
  const auto map = runner.snapshot()->best_map;

  Collected got;
  std::chrono::steady_clock::time_point t0;
  {
    session::LiveTopology live(shippedModel(), topologyOptions(), got.sink());
    live.request(map, 1, 1);
    while (!live.busy() && live.computed() == 0) std::this_thread::sleep_for(1ms);
    // While 1 is computed: 2 waits, 3 replaces it, 3 again is ignored.
    live.request(map, 2, 2);
    live.request(map, 3, 3);
    live.request(map, 3, 3);
    ASSERT_TRUE(live.waitIdle(600s));
    EXPECT_EQ(live.requests(), 3u);
    EXPECT_EQ(live.dropped(), 1u);
    EXPECT_EQ(live.computed(), 2u);
    ASSERT_EQ(got.results.size(), 2u);
    EXPECT_EQ(got.results[0]->steps, 1u);
    EXPECT_EQ(got.results[1]->steps, 3u);
    EXPECT_EQ(differingCells(got.results[0]->data->topo.labels, got.results[1]->data->topo.labels), 0);

    // Destroyed while computing: the computation is abandoned at its next safe point, nothing more is published.
    live.request(map, 4, 4);
    while (!live.busy()) std::this_thread::sleep_for(1ms);
    t0 = std::chrono::steady_clock::now();
  }
  const double stop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("stopped in %.3f s (one computation: %.3f s)\n", stop_seconds, got.results[1]->seconds);
  EXPECT_EQ(got.results.size(), 2u);

  // A listener that outlives its LiveTopology does nothing.
  session::SlamRunner::BestMapListener orphan;
  {
    session::LiveTopology live(shippedModel(), topologyOptions());
    orphan = live.listener();
  }
  orphan(map, 5, 5, {});
}

TEST(LiveTopology, SessionDrawsTheLabelsAndTheGraphOverTheSlamMap) {
  session::Session s;
  s.openLog(GRIDTOPO_DATA_DIR "/slam/intel.clf.gz", 1500);
  mapping::TopologyBuilderOptions schedule;
  schedule.update_every = 100;
  EXPECT_THROW(s.setLiveTopology(true, schedule), std::runtime_error);  // no model yet
  EXPECT_FALSE(s.liveTopologyOn());
  s.openModel(GRIDTOPO_DATA_DIR "/models/places_model.yml");
  s.slamOptions() = slamOptions();
  s.topologyOptions().threads = 1;
  s.setLiveTopology(true, schedule);
  s.startSlam();
  ASSERT_TRUE(s.liveTopology());
  s.runner()->step(150);
  ASSERT_TRUE(s.runner()->waitIdle(600s));
  ASSERT_TRUE(s.liveTopology()->waitIdle(600s));
  // Every 100 updates and at the pause: 100, then 150 (the last result).
  EXPECT_EQ(s.liveTopology()->requests(), 2u);
  const auto r = s.liveTopologyResult();
  ASSERT_TRUE(r && r->data) << (r ? r->error : "no result");
  EXPECT_EQ(r->steps, 150u);

  // The SLAM view: the live topology's labelled map and graph over the SLAM map, with its caption.
  session::Layers layers;
  layers.particles = layers.best_path = layers.odometry = layers.scan = layers.scale_bar = false;
  layers.graph = layers.region_ids = layers.closures = false;
  session::ViewTransform v;
  double x0, y0, x1, y1;
  ASSERT_TRUE(s.bounds(session::ViewMode::Slam, x0, y0, x1, y1));
  cv::Mat screen(700, 900, CV_8UC3);
  v.fit(x0, y0, x1, y1, screen.cols, screen.rows);
  s.render(screen, session::ViewMode::Slam, v, layers);
  cv::Mat expected(screen.size(), CV_8UC3, cv::Scalar(72, 72, 72));
  session::MapRaster raster;
  raster.set(session::topologyImage(*r->data, layers.stage, true), r->data->map);
  raster.draw(expected, v);
  // Inside the live topology's map, below the caption, the screen is its labelled map.
  cv::Mat inside(screen.size(), CV_8UC3, cv::Scalar(0, 0, 0));
  session::MapRaster coverage;
  coverage.set(cv::Mat(r->data->map.grey.size(), CV_8UC3, cv::Scalar(255, 255, 255)), r->data->map);
  coverage.draw(inside, v);
  int compared = 0, same = 0, coloured = 0;
  for (int y = 40; y < screen.rows; ++y)
    for (int x = 0; x < screen.cols; ++x) {
      if (inside.at<cv::Vec3b>(y, x)[0] == 0) continue;
      ++compared;
      same += screen.at<cv::Vec3b>(y, x) == expected.at<cv::Vec3b>(y, x);
      const cv::Vec3b p = screen.at<cv::Vec3b>(y, x);
      coloured += p[0] != p[1] || p[1] != p[2];
    }
  std::printf("SLAM view: %d pixels compared, %d as the labelled map, %d coloured\n", compared, same, coloured);
  EXPECT_GT(compared, screen.total() / 4);
  EXPECT_EQ(same, compared);
  EXPECT_GT(coloured, compared / 50);  // labels visibly on the map
  // The caption says which scan the topology is of; the graph is drawn when asked for.
  cv::Mat caption = screen.clone();
  session::drawCaption(caption, session::liveTopologyCaption(*r));
  EXPECT_EQ(differingPixels(screen, caption, cv::Rect(0, 0, screen.cols, screen.rows)), 0);
  cv::Mat with_graph(screen.size(), CV_8UC3);
  layers.graph = true;
  s.render(with_graph, session::ViewMode::Slam, v, layers);
  cv::Mat graph_only = screen.clone();
  session::drawTopologyGraph(graph_only, v, *r->data, true, false);
  const cv::Rect below_caption(0, 40, screen.cols, screen.rows - 40);
  const int graph_pixels = differingPixels(graph_only, screen, below_caption);
  std::printf("graph: %d pixels\n", graph_pixels);
  EXPECT_GT(graph_pixels, 200);
  EXPECT_EQ(differingPixels(with_graph, graph_only, below_caption), 0);

  // Off: no more live topology; the view is the SLAM map alone again.
  s.setLiveTopology(false);
  EXPECT_FALSE(s.liveTopology());
  EXPECT_FALSE(s.liveTopologyResult());
}
