// The map re-rendered from a trajectory (the paper's Fig. 2 cut-out): loop closure search, rendering at true poses
// in a simulated world with known walls, the window cut, the wall agreement measure and bad trajectories.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/trajectory_render.h"

using namespace gridtopo;

namespace {

/// A square of side `side` driven counter-clockwise from the origin in steps of `step`, `laps` times.
std::vector<TimedPose> squarePath(double side, double step, int laps) {
  std::vector<TimedPose> out;
  const int per_side = static_cast<int>(std::lround(side / step));
  double t = 0;
  for (int lap = 0; lap < laps; ++lap)
    for (int s = 0; s < 4; ++s)
      for (int k = 0; k < per_side; ++k) {
        const double a = k * step;
        const double xs[4] = {a, side, side - a, 0}, ys[4] = {0, a, side, side - a};
        out.push_back({t, {xs[s], ys[s], s * M_PI / 2}});
        t += 0.1;
      }
  return out;
}

/// Distance from (x, y) to the nearest wall of the plan.
double distanceToWalls(const sim::FloorPlan& plan, double x, double y) {
  double best = 1e9;
  for (const auto& w : plan.walls) {
    const double dx = w.x1 - w.x0, dy = w.y1 - w.y0, len2 = dx * dx + dy * dy;
    const double t = len2 > 0 ? std::clamp(((x - w.x0) * dx + (y - w.y0) * dy) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(x - (w.x0 + t * dx), y - (w.y0 + t * dy)));
  }
  return best;
}

struct OfficeRun {
  sim::FloorPlan plan = sim::FloorPlan::officeLoop();
  sim::SimLog log;
  std::vector<TimedPose> truth;
  OfficeRun() {
    sim::SimOptions so;
    so.range_sigma = 0.005;
    so.seed = 3;
    log = sim::simulate(plan, sim::officeLoopWaypoints(1), so);
    truth = log.timedTruth();
  }
};

}  // namespace

TEST(TrajectoryRender, FirstLoopClosureIsWhereTheSquareComesBack) {
  const auto path = squarePath(10.0, 0.1, 2);  // 400 poses a lap
  const auto lc = slam::firstLoopClosure(path, 0.5, 30.0);
  ASSERT_TRUE(lc.has_value());
  // Pose 400 is the origin again (40 m driven); with a 0.5 m radius the closure starts 0.5 m before it, at pose
  // 395 (on the last side, 0.5 m from the origin), nearest to pose 0.
  EXPECT_EQ(lc->later, 395u);
  EXPECT_EQ(lc->earlier, 0u);
  EXPECT_NEAR(lc->distance, 0.5, 1e-9);
  EXPECT_NEAR(lc->travelled, 39.5, 1e-6);
  // One side back and forth never travels 30 m before coming back: no closure with a longer minimum travel.
  EXPECT_FALSE(slam::firstLoopClosure(path, 0.5, 100.0).has_value());
  std::vector<TimedPose> line;
  for (int k = 0; k < 500; ++k) line.push_back({k * 0.1, {k * 0.1, 0, 0}});
  EXPECT_FALSE(slam::firstLoopClosure(line).has_value());
}

TEST(TrajectoryRender, WallsAtTruePosesLieOnThePlansWallsAtOneCentimetre) {
  const OfficeRun run;
  slam::TrajectoryRenderOptions o;
  o.resolution = 0.01;
  o.window = slam::MapWindow{0.5, 0.5, 8.5, 6.5};  // the south-west corridor corner and two rooms' doors
  std::size_t inserted = 0;
  const auto map = slam::mapFromTrajectory(run.log.records, run.truth, o, &inserted);
  EXPECT_GT(inserted, 50u);
  EXPECT_LT(inserted, run.truth.size());  // scans far from the window are skipped
  const cv::Mat img = slam::renderWindow(map, *o.window);
  EXPECT_EQ(img.cols, 801);
  EXPECT_EQ(img.rows, 601);
  std::size_t occupied = 0, on_wall = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c)
      if (img.at<unsigned char>(r, c) < 90) {  // p > 0.65
        ++occupied;
        const double x = (map.cellIndex(o.window->x0) + c + 0.5) * 0.01;
        const double y = (map.cellIndex(o.window->y0) + (img.rows - 1 - r) + 0.5) * 0.01;
        if (distanceToWalls(run.plan, x, y) <= 0.025) ++on_wall;
      }
  EXPECT_GT(occupied, 1500u);
  EXPECT_GT(static_cast<double>(on_wall) / occupied, 0.97) << on_wall << " of " << occupied;
  // Nothing is drawn outside the window's cells: the grid's tiles stay within the window plus the reach.
  int x0, y0, x1, y1;
  map.cellBounds(x0, y0, x1, y1);
  EXPECT_GE(x0 * 0.01, o.window->x0 - o.reach - 1.0);
  EXPECT_LE(x1 * 0.01, o.window->x1 + o.reach + 1.0);
}

TEST(TrajectoryRender, TheWindowCutChangesAlmostNothingInsideTheWindow) {
  const OfficeRun run;
  slam::TrajectoryRenderOptions whole;
  whole.resolution = 0.02;
  slam::TrajectoryRenderOptions cut = whole;
  cut.window = slam::MapWindow{2.0, 2.0, 9.0, 7.0};
  cut.reach = 30.0;  // every scan: only the beam cut differs
  const cv::Mat a = slam::renderWindow(slam::mapFromTrajectory(run.log.records, run.truth, whole), *cut.window);
  const cv::Mat b = slam::renderWindow(slam::mapFromTrajectory(run.log.records, run.truth, cut), *cut.window);
  ASSERT_EQ(a.size(), b.size());
  auto cls = [](unsigned char g) { return g < 90 ? 0 : g > 166 ? 2 : 1; };
  std::size_t same = 0;
  for (int r = 0; r < a.rows; ++r)
    for (int c = 0; c < a.cols; ++c) same += cls(a.at<unsigned char>(r, c)) == cls(b.at<unsigned char>(r, c));
  EXPECT_GT(static_cast<double>(same) / a.total(), 0.99);
}

TEST(TrajectoryRender, WallAgreementSeesAShiftedHalfOfTheRun) {
  const OfficeRun run;
  slam::TrajectoryRenderOptions first, second;
  first.resolution = second.resolution = 0.01;
  first.window = second.window = slam::MapWindow{0.5, 0.5, 19.5, 11.5};
  const std::size_t half = run.truth.size() / 2;
  first.end_pose = second.first_pose = half;
  const auto a = slam::mapFromTrajectory(run.log.records, run.truth, first);
  const auto good = slam::wallAgreement(a, slam::mapFromTrajectory(run.log.records, run.truth, second), *first.window);
  auto shifted = run.truth;
  for (std::size_t k = half; k < shifted.size(); ++k) {
    shifted[k].pose.x += 0.07;  // every wall of the plan (along x or y) moves 7 cm across itself
    shifted[k].pose.y += 0.07;
  }
  const auto bad = slam::wallAgreement(a, slam::mapFromTrajectory(run.log.records, shifted, second), *first.window);
  EXPECT_GT(good.cells, 1000u);
  EXPECT_LE(good.median, 0.011);
  EXPECT_GT(good.within_2cells, 0.85);
  std::cout << "good: median " << good.median << " p90 " << good.p90 << " within " << good.within_2cells
            << "; shifted: median " << bad.median << " p90 " << bad.p90 << " within " << bad.within_2cells << "\n";
  EXPECT_GE(bad.median, 0.05);
  EXPECT_GE(bad.p90, 0.065);
  EXPECT_LT(bad.within_2cells, 0.3);
}

TEST(TrajectoryRender, ATrajectoryOfAnotherLogIsRefused) {
  const OfficeRun run;
  auto traj = run.truth;
  traj[5].timestamp += 0.5;
  try {
    slam::mapFromTrajectory(run.log.records, traj, {});
    FAIL() << "no TrajectoryMismatch";
  } catch (const slam::TrajectoryMismatch& e) {
    EXPECT_EQ(e.pose_index, 5u);
    EXPECT_NE(std::string(e.what()).find("pose 6"), std::string::npos) << e.what();
  }
  traj = run.truth;
  traj.push_back(traj.back());
  EXPECT_THROW(slam::mapFromTrajectory(run.log.records, traj, {}), slam::TrajectoryMismatch);
  // A shorter trajectory (a run with --max-scans) renders its first scans.
  traj.assign(run.truth.begin(), run.truth.begin() + 10);
  std::size_t inserted = 0;
  slam::mapFromTrajectory(run.log.records, traj, {}, &inserted);
  EXPECT_EQ(inserted, 10u);
}
