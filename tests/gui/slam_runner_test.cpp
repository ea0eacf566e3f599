#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <numeric>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/serialization/CArchive.h>

#include "gridtopo/core/error.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/places/occupancy.h"
#include "gridtopo/session/session.h"
#include "gridtopo/session/slam_runner.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/slam_outputs.h"
#include "common/same_outputs.h"
#include "test_helpers.h"

using namespace gridtopo;
using namespace std::chrono_literals;
using guitest::pixelsOf;
using testing_outputs::expectSameTrajectory;

namespace {
const std::string kIntel = GRIDTOPO_DATA_DIR "/slam/intel.clf.gz";
constexpr std::size_t kScans = 250;

std::shared_ptr<const std::vector<ScanRecord>> intelSlice() {
  static const auto s = [] {
    auto v = io::readScanLog(kIntel);
    v.resize(kScans);
    return std::make_shared<const std::vector<ScanRecord>>(std::move(v));
  }();
  return s;
}
slam::SlamOptions smallOptions() {
  slam::SlamOptions o;
  o.particles = 8;
  o.seed = 7;
  o.threads = 2;
  return o;
}
// The reference: the filter run directly, without the runner.
const std::vector<TimedPose>& directTrajectory() {
  static const auto t = [] {
    slam::RbpfSlam f(smallOptions());
    for (const auto& r : *intelSlice()) f.processScan(r);
    return f.trajectory();
  }();
  return t;
}
}  // namespace

TEST(SlamRunner, StartsPausedAndStepsOneFilterUpdateAtATime) {
  session::SlamRunner r(intelSlice(), smallOptions());
  ASSERT_TRUE(r.waitIdle(10s));
  auto s = r.snapshot();
  EXPECT_EQ(s->state, session::RunState::Paused);
  EXPECT_EQ(s->scans_fed, 0u);
  EXPECT_EQ(s->scans_total, kScans);
  r.step();
  ASSERT_TRUE(r.waitIdle(30s));
  s = r.snapshot();
  EXPECT_EQ(s->state, session::RunState::Paused);
  EXPECT_EQ(s->steps, 1u);
  EXPECT_EQ(s->stats.size(), 1u);
  r.step(5);
  ASSERT_TRUE(r.waitIdle(30s));
  s = r.snapshot();
  EXPECT_EQ(s->steps, 6u);
  // The scan that completed the 6th update is the last one fed.
  EXPECT_EQ(s->stats.back().scan_index + 1, s->scans_fed);
  EXPECT_EQ(s->particles.size(), 8u);
  double wsum = 0;
  for (const auto& p : s->particles) wsum += p.weight;
  EXPECT_NEAR(wsum, 1.0, 1e-9);
  EXPECT_GT(s->best_map.tileCount(), 0u);
  // Paused: the trajectory covers every scan fed.
  EXPECT_EQ(s->trajectory.size(), s->scans_fed);
  EXPECT_EQ(s->trajectory_scans, s->scans_fed);
  EXPECT_GT(s->rss_bytes, 0u);
  EXPECT_GE(s->peak_rss_bytes, s->rss_bytes);
}

TEST(SlamRunner, PlayPauseResumeGivesExactlyTheDirectRun) {
  session::RunnerOptions ro;
  ro.snapshot_interval = 0.0;  // a snapshot after every scan: the most interference the GUI can cause
  ro.trajectory_interval = 0.0;
  session::SlamRunner r(intelSlice(), smallOptions(), ro);
  r.step(3);
  ASSERT_TRUE(r.waitIdle(30s));
  r.play();
  r.pause();
  ASSERT_TRUE(r.waitIdle(30s));
  const auto mid = r.snapshot();
  EXPECT_TRUE(mid->state == session::RunState::Paused || mid->state == session::RunState::Finished);
  r.play();
  ASSERT_TRUE(r.waitIdle(60s));
  const auto s = r.snapshot();
  ASSERT_EQ(s->state, session::RunState::Finished);
  EXPECT_EQ(s->scans_fed, kScans);
  expectSameTrajectory(s->trajectory, directTrajectory());
  EXPECT_EQ(s->stats.size(), s->steps);
  EXPECT_GT(s->steps, 10u);
  EXPECT_GT(s->wall_seconds, 0.0);
  EXPECT_GT(s->scans_per_second, 0.0);
  // Snapshots taken earlier are untouched by the run that went on (copy-on-write tiles, immutable nodes).
  EXPECT_LE(mid->steps, s->steps);
  EXPECT_LE(mid->trajectory.size(), s->trajectory.size());
  for (std::size_t i = 0; i < mid->stats.size(); ++i) EXPECT_EQ(mid->stats[i].neff, s->stats[i].neff);
}

TEST(SlamRunner, StopEndsTheRunForGood) {
  session::SlamRunner r(intelSlice(), smallOptions());
  r.step(2);
  ASSERT_TRUE(r.waitIdle(30s));
  r.stop();
  ASSERT_TRUE(r.waitIdle(10s));
  const auto fed = r.snapshot()->scans_fed;
  EXPECT_EQ(r.snapshot()->state, session::RunState::Stopped);
  r.play();
  r.step();
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(r.snapshot()->scans_fed, fed);
  EXPECT_EQ(r.snapshot()->state, session::RunState::Stopped);
}

TEST(SlamRunner, BadOptionsAndEmptyLogsThrowBeforeAnyThreadStarts) {
  auto o = smallOptions();
  o.particles = 0;
  EXPECT_THROW(session::SlamRunner(intelSlice(), o), InputError);
  o = smallOptions();
  o.resolution = -0.05;
  EXPECT_THROW(session::SlamRunner(intelSlice(), o), InputError);
  EXPECT_THROW(session::SlamRunner(std::make_shared<const std::vector<ScanRecord>>(), smallOptions()), InputError);
}

TEST(SessionSlam, SavesTheSameFilesAsTheWritersAndSendsTheMapToTopology) {
  guitest::TempDir tmp;
  session::Session s;
  s.openLog(kIntel, kScans);
  s.slamOptions() = smallOptions();
  s.startSlam();
  EXPECT_THROW(s.saveSlamOutputs(tmp / "early"), std::runtime_error);  // nothing processed yet
  s.runner()->play();
  ASSERT_TRUE(s.runner()->waitIdle(60s));
  const auto snap = s.slamSnapshot();
  s.saveSlamOutputs(tmp / "out");
  for (const char* f : {"trajectory.txt", "map.png", "map_trajectory.png", "map.pgm", "map.yaml", "map.gridmap.gz",
                        "map.simplemap", "stats.txt", "options.ini"})
    EXPECT_TRUE(std::filesystem::is_regular_file(tmp / ("out/" + std::string(f)))) << f;
  expectSameTrajectory(io::readTrajectory(tmp / "out/trajectory.txt"), directTrajectory());
  const auto grid = io::readGridMap(tmp / "out/map.gridmap.gz");
  // The simple map holds one keyframe per filter update of the best particle (as gridtopo-slam writes it).
  {
    mrpt::maps::CSimpleMap sm;
    mrpt::io::CFileGZInputStream f(tmp / "out/map.simplemap");
    auto a = mrpt::serialization::archiveFrom(f);
    a >> sm;
    EXPECT_EQ(sm.size(), snap->steps);
  }
  // The ROS pair reads back to the same grid.
  const auto ros = io::readGridMap(tmp / "out/map.yaml");
  EXPECT_EQ(ros->getSizeX(), grid->getSizeX());
  const auto expected = slam::toOccupancyGrid(snap->best_map);
  EXPECT_EQ(grid->getSizeX(), expected.getSizeX());
  EXPECT_EQ(grid->getSizeY(), expected.getSizeY());
  // stats.txt is the run's (SlamRun::statsText: a row per processed scan with the process RSS), and options.ini the
  // RUN.ini that reruns the scans fed with gridtopo-slam.
  {
    std::ifstream stats(tmp / "out/stats.txt");
    std::string header;
    std::getline(stats, header);
    EXPECT_EQ(header, std::string("# ") + slam::kStatsColumns + " rss_kb");
    std::size_t rows = 0, closure_lines = 0;
    for (std::string l; std::getline(stats, l);) (l.rfind("# ", 0) == 0 ? closure_lines : rows) += 1;
    EXPECT_EQ(rows, snap->steps);
    EXPECT_GE(closure_lines, 2u);  // the loop closure's header and summary (no closure in 250 scans)
    std::ostringstream ini;
    ini << std::ifstream(tmp / "out/options.ini").rdbuf();
    EXPECT_EQ(ini.str().rfind("[slam_run]\ninput = " + std::filesystem::absolute(kIntel).lexically_normal().string() +
                                  "\noutput = " + tmp / "out" + "\nmax_scans = 250\n\n[slam]\n",
                              0),
              0u)
        << ini.str();
  }
  // The INI written back loads into the same options.
  session::Session s2;
  s2.openSlamIni(tmp / "out/options.ini");
  EXPECT_EQ(s2.slamOptions().particles, 8);
  EXPECT_EQ(s2.slamOptions().seed, 7u);

  s.useSlamMap();
  EXPECT_EQ(s.map().cols(), static_cast<int>(expected.getSizeX()));
  EXPECT_EQ(s.map().rows(), static_cast<int>(expected.getSizeY()));
  EXPECT_EQ(cv::countNonZero(s.map().grey != io::gridToImage(expected)), 0);
}

// GUI: SLAM on a log, Topology > use the SLAM map, run. The SLAM map is a probabilistic grid whatever its display
// name ("<slam map, N scans>"): it is thresholded and opened as the same map read back from map.gridmap.gz.
TEST(SessionSlam, TheSlamMapIsLabelledAsTheGridmapItIsSavedAs) {
  guitest::TempDir tmp;
  guitest::handMadeModel().save(tmp / "model.yml");
  session::Session s;
  s.openLog(kIntel, kScans);
  s.slamOptions() = smallOptions();
  s.openModel(tmp / "model.yml");
  s.startSlam();
  s.runner()->play();
  ASSERT_TRUE(s.runner()->waitIdle(60s));
  s.useSlamMap();
  ASSERT_NO_THROW(s.runTopology());
  const auto* t = s.topology();
  ASSERT_NE(t, nullptr);
  // A sensible share of the map is free and labelled: most cells the grid threshold calls free survive the
  // one-cell opening, and every free cell of a classified lattice block has a label.
  const topology::TopologyOptions opt;
  const int grid_free = cv::countNonZero(s.map().grey >= opt.grid_free_threshold);
  const auto occ_free = static_cast<int>(places::countFree(t->occ));
  ASSERT_GT(grid_free, 1000);
  EXPECT_GT(occ_free, grid_free / 2);
  EXPECT_LE(occ_free, grid_free);
  EXPECT_GT(cv::countNonZero(t->topo.labels <= 2), occ_free * 9 / 10);
  EXPECT_FALSE(t->topo.graph.nodes.empty());
  // The label painter uses the same free cells (before the opening).
  s.startLabelling();
  const auto h = s.canvas().histogram();
  EXPECT_EQ(h[0], grid_free);

  // The same map, opened as a file, gives the same labels.
  s.saveSlamOutputs(tmp / "out");
  session::Session f;
  f.openModel(tmp / "model.yml");
  f.openMap(tmp / "out/map.gridmap.gz");
  ASSERT_EQ(cv::countNonZero(f.map().grey != s.map().grey), 0);
  f.runTopology();
  EXPECT_EQ(cv::countNonZero(f.topology()->topo.labels != t->topo.labels), 0);
  EXPECT_EQ(f.topology()->topo.graph.nodes.size(), t->topo.graph.nodes.size());
}

TEST(SessionSlam, SelectingAParticleGivesItsPoseWeightAndPath) {
  session::Session s;
  s.openLog(kIntel, kScans);
  s.slamOptions() = smallOptions();
  s.startSlam();
  s.runner()->step(4);
  ASSERT_TRUE(s.runner()->waitIdle(30s));
  const auto snap = s.slamSnapshot();
  const auto& p = snap->particles[3];
  const auto& sel = s.select(session::ViewMode::Slam, p.pose.x + 0.001, p.pose.y, 0.002);
  ASSERT_EQ(sel.kind, session::Selection::Kind::Particle);
  // Particles may coincide: the one picked is at that pose.
  EXPECT_NEAR(sel.particle_pose.x, p.pose.x, 1e-12);
  EXPECT_EQ(sel.particle_path.size(), 4u);  // one node per filter update
  EXPECT_NE(sel.text.find("weight"), std::string::npos);
  // Nothing within the radius: not a particle.
  EXPECT_NE(s.select(session::ViewMode::Slam, p.pose.x + 50, p.pose.y, 0.1).kind, session::Selection::Kind::Particle);
}

TEST(SessionSlam, RelationsErrorUsesOnlyRelationsInsideTheProcessedPart) {
  session::Session s;
  s.openLog(kIntel, 1200);
  s.openRelations(GRIDTOPO_DATA_DIR "/slam/intel.relations.gz");
  s.slamOptions() = smallOptions();
  s.startSlam();
  s.runner()->play();
  ASSERT_TRUE(s.runner()->waitIdle(60s));
  const auto snap = s.slamSnapshot();
  const auto err = s.relationsError(*snap);
  ASSERT_TRUE(err.has_value());
  std::size_t inside = 0;
  for (const auto& r : s.relations()) inside += std::max(r.t1, r.t2) <= snap->trajectory.back().timestamp;
  EXPECT_EQ(err->translational.count, inside);
  EXPECT_GT(inside, 5u);
  EXPECT_LT(err->translational.mean, 0.2);  // 250 scans of Intel: no loop yet, small local errors
}

namespace {
// Loop closure on the first 1500 scans of Intel with 8 particles: the robot comes back twice (2 closures), as in
// MapApp.LoopClosureRunMatchesGridtopoSlam.
constexpr std::size_t kLoopScans = 1500;
slam::SlamOptions loopOptions() {
  slam::SlamOptions o;
  o.particles = 8;
  o.seed = 1;
  o.threads = 2;
  o.loop_closure.enabled = true;
  return o;
}
}  // namespace

// The loop closure's edges reach the GUI through the snapshot (at the pose graph's poses) and are drawn in their
// layer; the optimised map is the run's result, the best particle's map stays beside it for the "before" view.
TEST(SessionSlam, LoopClosuresAndTheOptimisedMapReachTheSnapshotAndTheView) {
  session::Session s;
  s.openLog(kIntel, kLoopScans);
  s.slamOptions() = loopOptions();
  s.startSlam();
  auto before = s.slamSnapshot();
  EXPECT_TRUE(before->loop_closure);
  EXPECT_TRUE(before->closures.empty());
  EXPECT_FALSE(before->optimised_map);
  s.runner()->play();
  ASSERT_TRUE(s.runner()->waitIdle(120s));
  const auto snap = s.slamSnapshot();
  ASSERT_EQ(snap->state, session::RunState::Finished);

  // The same run without the runner: its pose graph is the reference.
  auto scans = io::readScanLog(kIntel);
  scans.resize(kLoopScans);
  slam::SlamRun direct(std::make_shared<const std::vector<ScanRecord>>(std::move(scans)), loopOptions());
  direct.runToEnd();
  const auto& closer = *direct.loopCloser();
  ASSERT_EQ(closer.closures().size(), 2u);
  ASSERT_EQ(snap->closures.size(), 2u);
  const auto graph = closer.poses();
  for (std::size_t i = 0; i < snap->closures.size(); ++i) {
    const auto& c = snap->closures[i];
    EXPECT_EQ(c.node, closer.closures()[i].node);
    EXPECT_EQ(c.submap_node, closer.closures()[i].submap_node);
    EXPECT_FALSE(c.rejected);
    EXPECT_LT(c.submap_node, c.node);
    for (const slam::Pose2& p : {c.newest, c.submap}) EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
    EXPECT_EQ(c.newest.x, graph[c.node].x);
    EXPECT_EQ(c.newest.y, graph[c.node].y);
    EXPECT_EQ(c.submap.x, graph[c.submap_node].x);
    EXPECT_EQ(c.submap.y, graph[c.submap_node].y);
    // A revisit: the whole submap (submap_nodes processed scans from its first node) lies before the closing scan.
    EXPECT_GT(c.node - c.submap_node, static_cast<std::size_t>(loopOptions().loop_closure.submap_nodes));
  }
  // The optimised map is the run's result map, and what Send map to topology takes.
  ASSERT_TRUE(snap->optimised_map);
  EXPECT_EQ(snap->optimised_map_scans, kLoopScans);
  const cv::Mat optimised = io::gridToImage(slam::toOccupancyGrid(*snap->optimised_map));
  const cv::Mat expected = io::gridToImage(slam::toOccupancyGrid(direct.resultMap()));
  ASSERT_EQ(optimised.size(), expected.size());
  EXPECT_EQ(cv::countNonZero(optimised != expected), 0);
  const cv::Mat particle = io::gridToImage(slam::toOccupancyGrid(snap->best_map));
  EXPECT_TRUE(particle.size() != optimised.size() || cv::countNonZero(particle != optimised) > 0)
      << "the best particle's map should differ from the optimised one";
  s.useSlamMap();
  EXPECT_EQ(s.map().cols(), optimised.cols);
  EXPECT_EQ(cv::countNonZero(s.map().grey != optimised), 0);

  // The view: the closures' layer draws pixels of their colour, and only it does.
  session::ViewTransform v;
  double x0, y0, x1, y1;
  ASSERT_TRUE(s.bounds(session::ViewMode::Slam, x0, y0, x1, y1));
  v.fit(x0, y0, x1, y1, 600, 500);
  session::Layers only;
  only.map = only.particles = only.best_path = only.odometry = only.scan = only.scale_bar = false;
  cv::Mat screen(500, 600, CV_8UC3);
  s.render(screen, session::ViewMode::Slam, v, only);
  EXPECT_GT(pixelsOf(screen, session::kClosureColour), 20);
  for (const auto& c : snap->closures) {  // a dot at each end
    const cv::Point2d q = v.toScreen(c.submap.x, c.submap.y);
    EXPECT_EQ(screen.at<cv::Vec3b>(static_cast<int>(std::lround(q.y)), static_cast<int>(std::lround(q.x))),
              cv::Vec3b(255, 0, 255));
  }
  only.closures = false;
  s.render(screen, session::ViewMode::Slam, v, only);
  EXPECT_EQ(pixelsOf(screen, session::kClosureColour), 0);
  // The map before and after: the optimised-map toggle switches the map drawn at once.
  session::Layers maps = only;
  maps.map = true;
  cv::Mat after(500, 600, CV_8UC3), before_view(500, 600, CV_8UC3);
  s.render(after, session::ViewMode::Slam, v, maps);
  maps.optimised_map = false;
  s.render(before_view, session::ViewMode::Slam, v, maps);
  EXPECT_GT(cv::countNonZero(cv::Mat(after != before_view).reshape(1)), 100);
}

TEST(SlamRunner, WithoutTheLoopClosureTheSnapshotHasNoClosuresNorOptimisedMap) {
  slam::SlamOptions o = smallOptions();
  o.loop_closure.enabled = false;
  session::SlamRunner r(intelSlice(), o);
  r.play();
  ASSERT_TRUE(r.waitIdle(60s));
  const auto s = r.snapshot();
  EXPECT_FALSE(s->loop_closure);
  EXPECT_TRUE(s->closures.empty());
  EXPECT_FALSE(s->optimised_map);
  EXPECT_EQ(s->optimised_map_scans, 0u);
  // The run's map is then the best particle's.
  EXPECT_EQ(&s->resultMap(), &s->best_map);
}
