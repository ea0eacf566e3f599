// The loop closure beside the filter (loop_closure.h) on simulated buildings with a known trajectory:
//  - a large loop with long featureless corridors and odometry that is 6 % long: the filter alone comes back to
//    the start more than a metre off (the corridors do not observe the position along them); with the pose graph
//    the revisit is joined to the start and the loop closes to within centimetres;
//  - two identical parallel corridors: a match against the look-alike corridor must be refused or must not pull
//    the map apart;
//  - the branch-and-bound search itself: it finds the exhaustive best pose of a window and refuses an ambiguous
//    one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "common/odometry_error.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/correlative_matcher.h"
#include "gridtopo/slam/loop_closure.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/prepared_scan.h"
#include "gridtopo/slam/slam_run.h"
#include <opencv2/imgcodecs.hpp>

using namespace gridtopo;

namespace {

slam::Pose2 toPose(const mrpt::math::TPose2D& p) { return {p.x, p.y, p.phi}; }

// A horizontal wall at height y from x0 to x1 with rectangular recesses of width w starting at `starts`, `depth`
// deep (signed: + towards larger y).
void addRecessedWall(sim::FloorPlan& p, double y, double x0, double x1, const std::vector<double>& starts, double w,
                     double depth) {
  double x = x0;
  for (double a : starts) {
    p.walls.push_back({x, y, a, y});
    p.walls.push_back({a, y, a, y + depth});
    p.walls.push_back({a, y + depth, a + w, y + depth});
    p.walls.push_back({a + w, y + depth, a + w, y});
    x = a + w;
  }
  p.walls.push_back({x, y, x1, y});
}

// A 60 m × 24 m ring of 2.5 m wide corridors around a solid block. The south and north corridors have features
// only near their ends (door recesses), so that in their middles the 10 m laser sees two bare walls for about
// 30 m; the west and east corridors have a recess each and the start area (south-west) a pillar.
sim::FloorPlan largeLoopPlan() {
  sim::FloorPlan p;
  addRecessedWall(p, 0, 0, 60, {4, 7, 52, 56}, 1.0, -0.5);       // south outer wall
  addRecessedWall(p, 2.5, 2.5, 57.5, {5.5, 50}, 1.0, 0.5);      // the block's south face
  addRecessedWall(p, 24, 0, 60, {3, 9, 50.5, 55}, 1.0, 0.5);     // north outer wall
  addRecessedWall(p, 21.5, 2.5, 57.5, {6, 49}, 1.0, -0.5);      // the block's north face
  p.walls.push_back({0, 0, 0, 11});
  p.walls.push_back({0, 11, -0.6, 11});
  p.walls.push_back({-0.6, 11, -0.6, 12.2});
  p.walls.push_back({-0.6, 12.2, 0, 12.2});
  p.walls.push_back({0, 12.2, 0, 24});
  p.walls.push_back({60, 0, 60, 14});
  p.walls.push_back({60, 14, 60.6, 14});
  p.walls.push_back({60.6, 14, 60.6, 15});
  p.walls.push_back({60.6, 15, 60, 15});
  p.walls.push_back({60, 15, 60, 24});
  p.walls.push_back({2.5, 2.5, 2.5, 21.5});
  p.walls.push_back({57.5, 2.5, 57.5, 21.5});
  p.addRectangle(1.0, 0.8, 1.3, 1.1);  // a pillar in the start corner
  return p;
}

// Start in the south corridor heading east (the door recesses of the start area ahead), once round counter-clockwise, and on past the start for 12 m.
std::vector<mrpt::math::TPose2D> largeLoopWaypoints() {
  return {{2.0, 1.25, 0}, {58.75, 1.25, 0}, {58.75, 22.75, 0}, {1.25, 22.75, 0}, {1.25, 1.25, 0}, {20, 1.25, 0}};
}

sim::SimLog largeLoopLog() {
  sim::SimOptions so;
  so.max_range = 10.0;
  so.scan_spacing = 0.3;
  so.odo_sigma_xy = 0.01;
  so.odo_sigma_theta = 0.02;
  so.odo_sigma_theta_per_m = 0.005;
  so.odo_drift_theta = 0.002;
  so.seed = 11;
  sim::SimLog log = sim::simulate(largeLoopPlan(), largeLoopWaypoints(), so);
  testing_scene::scaleOdometry(log, 0.06);
  return log;
}

struct LoopResult {
  double loop_xy = 0.0;    ///< the loop's opening: the return to the start relative to the start (m)
  double loop_th = 0.0;    ///< rad
  double max_xy = 0.0;     ///< the trajectory's error after aligning its first pose with the truth (m)
  std::size_t closures = 0;
};

// Runs SlamRun over `log` from the true start pose and measures the loop's opening.
LoopResult runLoop(const sim::SimLog& log, const slam::SlamOptions& o, const char* picture) {
  auto scans = std::make_shared<const std::vector<ScanRecord>>(log.records);
  slam::SlamRun run(scans, o);
  run.filter().setInitialPose(toPose(log.truth.front()));
  run.runToEnd();
  const std::vector<TimedPose> traj = run.trajectory();
  LoopResult r;
  if (run.loopCloser()) r.closures = run.loopCloser()->closures().size();
  const auto& truth = log.truth;
  // The loop's opening: the pose of the last pass nearest (in the truth) to the first pose, relative to the first
  // pose, against the true relative pose.
  std::size_t turn = 0;  // the first pose in the north corridor: the loop is under way
  while (turn < truth.size() && truth[turn].y < 20) ++turn;
  std::size_t back = turn;
  double best = 1e9;
  for (std::size_t i = turn; i < truth.size(); ++i) {
    const double d = std::hypot(truth[i].x - truth[0].x, truth[i].y - truth[0].y) +
                     std::abs(slam::wrapAngle(truth[i].phi - truth[0].phi));
    if (d < best) best = d, back = i;
  }
  const slam::Pose2 rt = slam::relative(toPose(truth[0]), toPose(truth[back]));
  const slam::Pose2 re = slam::relative(toPose(traj[0].pose), toPose(traj[back].pose));
  r.loop_xy = std::hypot(re.x - rt.x, re.y - rt.y);
  r.loop_th = std::abs(slam::wrapAngle(re.theta - rt.theta));
  for (std::size_t i = 0; i < traj.size(); ++i)
    r.max_xy = std::max(r.max_xy, std::hypot(traj[i].pose.x - truth[i].x, traj[i].pose.y - truth[i].y));
  if (std::getenv("GRIDTOPO_TEST_VERBOSE") && run.loopCloser())
    std::printf("%s", slam::closuresText(run.loopCloser()->closures(), run.loopCloser()->counts(), 0).c_str());
  if (std::getenv("GRIDTOPO_TEST_VERBOSE"))
    for (std::size_t i = 0; i < traj.size(); i += 25)
      std::printf("%zu est %.3f %.3f %.4f truth %.3f %.3f %.4f\n", i, traj[i].pose.x, traj[i].pose.y, traj[i].pose.phi,
                  truth[i].x, truth[i].y, truth[i].phi);
  if (const char* dir = std::getenv("GRIDTOPO_TEST_PICTURES"))
    cv::imwrite(std::string(dir) + "/" + picture, slam::renderMap(slam::toOccupancyGrid(run.resultMap()), traj));
  std::printf("%s: loop %.3f m %.2f deg, max error %.3f m, %zu closures\n", picture, r.loop_xy,
              r.loop_th * 57.29577951308232, r.max_xy, r.closures);
  return r;
}

slam::SlamOptions testOptions() {
  slam::SlamOptions o;
  o.particles = 10;
  o.threads = 2;
  o.seed = 3;
  o.loop_closure.enabled = true;
  return o;
}

// Two identical parallel corridors, A (y 0..2.5) and B (y 5..7.5), 30 m long, with the same door recesses, joined
// at their west ends by a connector (x 0..2.5); a wall block between them.
sim::FloorPlan lookAlikePlan() {
  sim::FloorPlan p;
  const std::vector<double> doors{6, 13, 21, 26};
  addRecessedWall(p, 0.0, 2.5, 30, doors, 1.0, -0.5);  // A's south wall
  addRecessedWall(p, 2.5, 2.5, 30, {9, 17}, 1.0, 0.5);  // A's north wall
  addRecessedWall(p, 5.0, 2.5, 30, doors, 1.0, -0.5);  // B's south wall: the same pattern as A's
  addRecessedWall(p, 7.5, 2.5, 30, {9, 17}, 1.0, 0.5);  // B's north wall
  p.walls.push_back({0, 0, 2.5, 0});
  p.walls.push_back({0, 0, 0, 7.5});
  p.walls.push_back({0, 7.5, 2.5, 7.5});
  p.walls.push_back({2.5, 2.5, 2.5, 5.0});  // the connector's east side
  p.walls.push_back({30, 0, 30, 2.5});      // A's and B's east ends
  p.walls.push_back({30, 5, 30, 7.5});
  return p;
}

}  // namespace

TEST(LoopClosure, ALookAlikeCorridorDoesNotPullTheMapApart) {
  // East along A, back west along A, up the connector and east along B: B's scans look like A's first pass, 5 m
  // to the south. A closure with A from B is wrong; it must be refused or unable to move the map.
  sim::SimOptions so;
  so.max_range = 10.0;
  so.scan_spacing = 0.3;
  so.odo_drift_theta = 0.002;
  so.seed = 5;
  const sim::SimLog log = sim::simulate(lookAlikePlan(),
                                        {{3, 1.25, 0}, {28.5, 1.25, 0}, {28.5, 1.25, 3.14159265358979},
                                         {1.25, 1.25, 3.14159265358979}, {1.25, 6.25, 0}, {28.5, 6.25, 0}},
                                        so);
  auto scans = std::make_shared<const std::vector<ScanRecord>>(log.records);
  slam::SlamRun run(scans, testOptions());
  run.filter().setInitialPose(toPose(log.truth.front()));
  run.runToEnd();
  const std::vector<TimedPose> traj = run.trajectory();
  // Every pose's error against the truth (the run starts at the true pose), and the closures that join a node in B
  // to a submap in A by a match more than a metre from the estimate.
  double max_err = 0.0;
  for (std::size_t i = 0; i < traj.size(); ++i)
    max_err = std::max(max_err, std::hypot(traj[i].pose.x - log.truth[i].x, traj[i].pose.y - log.truth[i].y));
  std::size_t wrong = 0;
  for (const auto& c : run.loopCloser()->closures())
    if (!c.rejected && log.truth[c.scan_index].y > 5 && log.truth[run.loopCloser()->scanIndexOf(c.submap_node)].y < 2.5)
      ++wrong;
  std::printf("look-alike corridors: max error %.3f m, %zu closures, %zu from B to A\n", max_err,
              run.loopCloser()->closures().size(), wrong);
  EXPECT_EQ(wrong, 0u);
  EXPECT_LT(max_err, 0.3);
  EXPECT_GT(run.loopCloser()->closures().size(), 0u);  // the return along A does close on A
}

TEST(LoopClosure, TheFilterAloneLeavesTheLargeLoopOpenAndThePoseGraphClosesIt) {
  const sim::SimLog log = largeLoopLog();
  slam::SlamOptions off = testOptions();
  off.loop_closure.enabled = false;
  const LoopResult alone = runLoop(log, off, "loop_closure_off.png");
  EXPECT_GT(alone.loop_xy, 1.0) << "the filter alone should not close this loop";
  EXPECT_EQ(alone.closures, 0u);

  const LoopResult closed = runLoop(log, testOptions(), "loop_closure_on.png");
  EXPECT_GT(closed.closures, 5u);
  EXPECT_LT(closed.loop_xy, 0.05);
  EXPECT_LT(closed.loop_th, 0.01);
}

TEST(LoopClosure, AHeadingErrorWhereTheOdometryDisagreedIsFoundAtTheRevisit) {
  // The loop closure alone (no filter) fed the true path of the large loop with two faults on the last leg (west
  // corridor, southwards, a few metres before the start): a "crowd" where the filter turns 0.3 rad per step on two
  // steps while the odometry is right (FR079 at t = 1515 s), then a slip where the odometry turns 0.3 rad per step
  // on two steps while the filter is right. The filter's path comes back 0.6 rad and metres off, beyond what the
  // loop's length alone opens the window to (window_theta_max, 0.5 rad): the suspect steps' disagreement must widen
  // the window in heading, and through its lever in translation, for the start to be found again.
  const sim::SimLog log = largeLoopLog();
  const slam::SlamOptions o = testOptions();
  slam::LoopCloser closer(o.loop_closure, o.motion);
  const auto& truth = log.truth;
  slam::Pose2 filter = toPose(truth.front());
  std::size_t crowd = 0, slip = 0;
  std::vector<slam::Pose2> filter_path;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    slam::Pose2 motion{0, 0, 0}, odometry{0, 0, 0};
    if (k > 0) {
      motion = odometry = slam::relative(toPose(truth[k - 1]), toPose(truth[k]));
      const bool west_leg = truth[k].x < 2.0 && truth[k].y < 20.0 && truth[k - 1].y > truth[k].y;
      if (west_leg && truth[k].y < 9.0 && crowd < 2) motion.theta += 0.3, ++crowd;
      else if (west_leg && truth[k].y < 7.0 && slip < 2) odometry.theta += 0.3, ++slip;
      filter = slam::compose(filter, motion);
    }
    filter_path.push_back(filter);
    const slam::PreparedScan ps = slam::prepareScan(log.records[k].scan, o.beams, o.resolution);
    closer.addScan(k, log.records[k].scan.timestamp, filter, motion, k > 0 ? &odometry : nullptr, ps);
  }
  ASSERT_EQ(crowd, 2u);
  ASSERT_EQ(slip, 2u);
  // The filter's own path ends rotated by the crowd's 0.6 rad.
  const slam::Pose2 true_end = slam::relative(toPose(truth.front()), toPose(truth.back()));
  const slam::Pose2 filter_end = slam::relative(filter_path.front(), filter_path.back());
  EXPECT_NEAR(std::abs(slam::wrapAngle(filter_end.theta - true_end.theta)), 0.6, 1e-6);
  // A closure that undoes it, and the optimised end within centimetres of the truth.
  double largest = 0.0;
  for (const auto& c : closer.closures())
    if (!c.rejected) largest = std::max(largest, c.offset_theta);
  const std::vector<slam::Pose2> poses = closer.finalPoses();
  const slam::Pose2 end = slam::relative(poses.front(), poses.back());
  const double err_xy = std::hypot(end.x - true_end.x, end.y - true_end.y);
  const double err_th = std::abs(slam::wrapAngle(end.theta - true_end.theta));
  std::printf("crowd and slip: %zu closures, largest heading offset %.3f rad; end %.3f m %.4f rad off\n",
              closer.closures().size(), largest, err_xy, err_th);
  EXPECT_GT(largest, 0.5);
  EXPECT_LT(err_xy, 0.1);
  EXPECT_LT(err_th, 0.01);
}

namespace {
// The loop closure alone fed the large loop's true path with one fault on the last leg (west corridor, southwards,
// a few metres before the start): two steps where the odometry slipped by 0.15 rad each and the filter, whose scan
// match failed there, followed it (its pose drawn from the motion model). Filter and odometry agree, so the steps
// are not suspect: only the `matched` flag says that these two motions are odometry, not matches. Returns the
// final poses' end relative to the start, and the closures.
slam::Pose2 unmatchedSlipEnd(const sim::SimLog& log, bool flag_unmatched, bool soften, std::size_t* accepted) {
  slam::SlamOptions o = testOptions();
  o.loop_closure.unmatched_steps_as_odometry = soften;
  slam::LoopCloser closer(o.loop_closure, o.motion);
  const auto& truth = log.truth;
  slam::Pose2 filter = toPose(truth.front());
  std::size_t slipped = 0;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    slam::Pose2 motion{0, 0, 0};
    bool matched = true;
    if (k > 0) {
      motion = slam::relative(toPose(truth[k - 1]), toPose(truth[k]));
      const bool west_leg = truth[k].x < 2.0 && truth[k].y < 20.0 && truth[k - 1].y > truth[k].y;
      if (west_leg && truth[k].y < 9.0 && slipped < 2) motion.theta += 0.15, ++slipped, matched = !flag_unmatched;
      filter = slam::compose(filter, motion);
    }
    const slam::PreparedScan ps = slam::prepareScan(log.records[k].scan, o.beams, o.resolution);
    closer.addScan(k, log.records[k].scan.timestamp, filter, motion, k > 0 ? &motion : nullptr, ps, matched);
  }
  EXPECT_EQ(slipped, 2u);
  *accepted = 0;
  for (const auto& c : closer.closures()) *accepted += !c.rejected;
  const std::vector<slam::Pose2> poses = closer.finalPoses();
  return slam::relative(poses.front(), poses.back());
}
}  // namespace

TEST(LoopClosure, AStepWhoseMatchFailedBendsAtTheRevisitAsTheOdometryWould) {
  // The campus with 20 particles (seeds 3, 4, 6, 8 before): where the filter's matches failed it followed the
  // drifting odometry, and stiff edges that called those steps matches good to millimetres made the correct
  // closures at the return disagree with the graph: refused, or the graph bent elsewhere.
  const sim::SimLog log = largeLoopLog();
  const slam::Pose2 true_end = slam::relative(toPose(log.truth.front()), toPose(log.truth.back()));
  const auto error = [&](const slam::Pose2& end) {
    return std::make_pair(std::hypot(end.x - true_end.x, end.y - true_end.y),
                          std::abs(slam::wrapAngle(end.theta - true_end.theta)));
  };
  std::size_t accepted_soft = 0, accepted_stiff = 0, accepted_unflagged = 0;
  const auto soft = error(unmatchedSlipEnd(log, true, true, &accepted_soft));
  const auto stiff = error(unmatchedSlipEnd(log, true, false, &accepted_stiff));
  const auto unflagged = error(unmatchedSlipEnd(log, false, true, &accepted_unflagged));
  std::printf("unmatched slip of 0.3 rad: end %.3f m %.4f rad off with the motion model's edges (%zu closures), "
              "%.3f m %.4f rad with stiff edges (%zu), %.3f m %.4f rad when the steps say matched (%zu)\n",
              soft.first, soft.second, accepted_soft, stiff.first, stiff.second, accepted_stiff, unflagged.first,
              unflagged.second, accepted_unflagged);
  EXPECT_LT(soft.first, 0.1);
  EXPECT_LT(soft.second, 0.01);
  // The option off and the flag unset are the same stiff graph.
  EXPECT_EQ(stiff, unflagged);
  EXPECT_GT(stiff.first, 3.0 * soft.first + 0.05);
}

TEST(LoopClosure, TheFiltersPathSaysWhichPosesCameFromAFailedMatch) {
  // A scan with no return at all cannot be matched: every particle falls back to the odometry proposal, and its
  // node in the particle's path says so; the scans before and after it are matched.
  sim::SimLog log = largeLoopLog();
  log.records.resize(12);
  ScanRecord& blind = log.records[8];
  std::fill(blind.scan.ranges.begin(), blind.scan.ranges.end(), static_cast<float>(blind.scan.max_range));
  std::fill(blind.scan.valid.begin(), blind.scan.valid.end(), std::uint8_t{0});
  slam::SlamOptions o = testOptions();
  o.loop_closure.enabled = false;
  o.linear_update = 0.0;
  o.angular_update = 0.0;
  slam::RbpfSlam filter(o);
  filter.setInitialPose(toPose(log.truth.front()));
  for (const ScanRecord& r : log.records) filter.processScan(r);
  std::vector<std::size_t> unmatched;
  for (const slam::TrajectoryNode* n = filter.bestParticle().node.get(); n; n = n->parent.get())
    if (!n->matched) unmatched.push_back(n->scan_index);
  for (const slam::Particle& p : filter.particles()) {
    std::size_t count = 0;
    for (const slam::TrajectoryNode* n = p.node.get(); n; n = n->parent.get()) count += !n->matched;
    EXPECT_EQ(count, 1u);
  }
  ASSERT_EQ(unmatched.size(), 1u);
  EXPECT_EQ(unmatched.front(), 8u);
}

namespace {
// The loop closure alone fed the large loop's path with a heading drift of 0.01 degrees per step (5.6 degrees over
// the loop: it comes back metres off, within the windowed search's reach); with `force_at` > 0, a closure forced in at that node that
// puts it 3 m and 0.3 rad away from where it truly is relative to node 5 (the start). Returns the final poses.
std::vector<slam::Pose2> driftingLoopPoses(const sim::SimLog& log, std::size_t force_at,
                                           const slam::LoopClosureRecord** forced_record, slam::LoopCloser& closer) {
  const slam::SlamOptions o = testOptions();
  const auto& truth = log.truth;
  slam::Pose2 filter = toPose(truth.front());
  std::size_t forced_index = 0;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    slam::Pose2 motion{0, 0, 0};
    if (k > 0) {
      motion = slam::relative(toPose(truth[k - 1]), toPose(truth[k]));
      motion.theta += 0.01 * M_PI / 180.0;
      filter = slam::compose(filter, motion);
    }
    const slam::PreparedScan ps = slam::prepareScan(log.records[k].scan, o.beams, o.resolution);
    closer.addScan(k, log.records[k].scan.timestamp, filter, motion, nullptr, ps);
    if (force_at > 0 && k == force_at) {
      const slam::Pose2 truly = slam::relative(toPose(truth[5]), toPose(truth[k]));
      closer.addExternalClosure(5, {truly.x + 3.0, truly.y, truly.theta + 0.3}, 0.05, 0.0125);
      forced_index = closer.closures().size() - 1;
    }
  }
  if (forced_record) *forced_record = force_at > 0 ? &closer.closures()[forced_index] : nullptr;
  return closer.finalPoses();
}
}  // namespace

TEST(LoopClosure, AClosureForcedInAtAWrongPlaceIsSwitchedOffAndTheMapStaysAsWithoutIt) {
  const sim::SimLog log = largeLoopLog();
  const slam::SlamOptions o = testOptions();
  // Where the path first comes back within 3 m of the start after the loop: there the windowed search closes too.
  std::size_t back = 0;
  for (std::size_t k = 100; k < log.truth.size() && !back; ++k)
    if (std::hypot(log.truth[k].x - log.truth[5].x, log.truth[k].y - log.truth[5].y) < 3.0) back = k;
  ASSERT_GT(back, 0u);
  slam::LoopCloser plain(o.loop_closure, o.motion), forced(o.loop_closure, o.motion);
  const std::vector<slam::Pose2> without = driftingLoopPoses(log, 0, nullptr, plain);
  const slam::LoopClosureRecord* record = nullptr;
  const std::vector<slam::Pose2> with = driftingLoopPoses(log, back, &record, forced);
  ASSERT_NE(record, nullptr);
  ASSERT_EQ(without.size(), with.size());
  double largest_difference = 0.0, err_without = 0.0, err_with = 0.0;
  for (std::size_t k = 0; k < with.size(); ++k) {
    largest_difference = std::max(largest_difference, std::hypot(with[k].x - without[k].x, with[k].y - without[k].y));
    err_without = std::max(err_without, std::hypot(without[k].x - log.truth[k].x, without[k].y - log.truth[k].y));
    err_with = std::max(err_with, std::hypot(with[k].x - log.truth[k].x, with[k].y - log.truth[k].y));
  }
  std::printf("forced closure at node %zu: residual %.1f deviations, %s; largest error %.3f m without it, %.3f m "
              "with it; the two results differ by at most %.4f m\n",
              back, record->residual, record->rejected ? "switched off" : "kept", err_without, err_with,
              largest_difference);
  EXPECT_TRUE(record->rejected);
  EXPECT_GT(record->residual, o.loop_closure.outlier_sigmas);
  EXPECT_GT(plain.closures().size(), 5u);  // the windowed search closes the loop on its own
  EXPECT_LT(err_without, 0.5);                // measured 0.369 m (the largest over every pose)
  EXPECT_LT(err_with, err_without + 0.02);    // no worse with it (0.342 m)
  // Once it is out, the graph is optimised again from where the wrong closure had pulled it: the same result to a
  // few centimetres (0.040 m), where keeping it would bend the loop by metres.
  EXPECT_LT(largest_difference, 0.1);
  EXPECT_THROW(forced.addExternalClosure(forced.nodes() - 1, {0, 0, 0}, 0.05, 0.01), std::invalid_argument);
}

namespace {
// Points every 5 cm along a wall y = const from x0 to x1, and a small L-shaped feature at (fx, fy).
void addWall(std::vector<slam::Point2>& pts, double y, double x0, double x1) {
  for (double x = x0; x <= x1 + 1e-9; x += 0.05) pts.push_back({x, y});
}
void addCorner(std::vector<slam::Point2>& pts, double fx, double fy) {
  for (double d = 0; d <= 0.6; d += 0.05) {
    pts.push_back({fx + d, fy});
    pts.push_back({fx, fy + d});
  }
}
}  // namespace

TEST(CorrelativeMatcher, FindsTheExhaustiveBestPoseOfTheWindow) {
  // A room-like submap: two walls and two corners; the query is the same points seen from a pose
  // (0.73, -0.41, 0.12) away from the window's centre.
  std::vector<slam::Point2> submap;
  addWall(submap, 0.0, 0.0, 8.0);
  addWall(submap, 3.0, 0.0, 8.0);
  addCorner(submap, 2.0, 0.0);
  addCorner(submap, 6.0, 1.0);
  const slam::CorrelationGrid grid(submap, 0.05, 0.07, 6, 0.03);
  const slam::Pose2 truth{0.73, -0.41, 0.12};
  std::vector<slam::Point2> query;
  for (const auto& p : submap) {  // the submap's points expressed in the frame of `truth`
    const slam::Pose2 q = slam::relative(truth, {p.x, p.y, 0.0});
    query.push_back({q.x, q.y});
  }
  slam::SearchWindow w;
  w.center = {0.0, 0.0, 0.0};
  w.xy = 1.5;
  w.theta = 0.2;
  const auto found = slam::branchAndBoundSearch(grid, query, w, 0.5);
  ASSERT_TRUE(found.has_value());
  const slam::CorrelativeMatch m = slam::refineMatch(grid, query, found->pose, 0.005);
  EXPECT_NEAR(m.pose.x, truth.x, 0.01);
  EXPECT_NEAR(m.pose.y, truth.y, 0.01);
  EXPECT_NEAR(m.pose.theta, truth.theta, 0.003);
  EXPECT_GT(m.score, 0.85);  // the search value is quantised to cell centres
  // Nothing else in the window comes close: the second-best pose further than 0.6 m scores far less.
  const slam::Point2 at{m.pose.x, m.pose.y};
  EXPECT_FALSE(slam::branchAndBoundSearch(grid, query, w, 0.9 * m.score, &at, 0.6).has_value());
  // Outside the window the match is not found.
  w.center = {-1.0, 1.5, 0.0};
  w.xy = 0.5;
  const auto outside = slam::branchAndBoundSearch(grid, query, w, 0.9);
  EXPECT_FALSE(outside.has_value());
}

TEST(CorrelativeMatcher, EachLevelBoundsTheFinestOverItsSpan) {
  // Level h at cell (cx, cy) is the maximum of level 0 over [cx, cx + 2^h) x [cy, cy + 2^h): checked against the
  // definition on every cell from 2^h + 3 cells left of and below the lattice to 3 cells beyond it (the levels
  // store only the cells where that maximum can be non-zero), and the storage stays within the lattice plus the
  // low-side margins.
  std::vector<slam::Point2> pts;
  addWall(pts, 0.0, 0.0, 3.0);
  addCorner(pts, 1.0, 0.0);
  addWall(pts, 1.2, 0.5, 2.0);
  const int depth = 4;
  const slam::CorrelationGrid grid(pts, 0.05, 0.07, depth, 0.03);
  const int x1 = grid.cellX(3.0) + 8, y1 = grid.cellY(1.6) + 8;  // past the last point plus its margin
  int nonzero = 0;
  for (int cy = -3; cy <= y1; ++cy)
    for (int cx = -3; cx <= x1; ++cx) nonzero += grid.value(0, cx, cy) > 0;
  ASSERT_GT(nonzero, 100);
  for (int h = 1; h <= depth; ++h) {
    const int span = 1 << h;
    for (int cy = -span - 3; cy <= y1; ++cy)
      for (int cx = -span - 3; cx <= x1; ++cx) {
        int m = 0;
        for (int dy = 0; dy < span; ++dy)
          for (int dx = 0; dx < span; ++dx) m = std::max(m, grid.value(0, cx + dx, cy + dy));
        ASSERT_EQ(grid.value(h, cx, cy), m) << "level " << h << " cell " << cx << ", " << cy;
      }
  }
  // Lattice about (3 m + 2 margins) x (1.8 m + 2 margins) at 5 cm: a byte per cell and level plus the margins,
  // four bytes per cell for the nearest point.
  const double cells = (x1 - 8 + 1.0) * (y1 - 8 + 1.0);
  EXPECT_LT(static_cast<double>(grid.bytes()), cells * (depth + 1 + 4) * 1.6);
}

TEST(CorrelativeMatcher, AFeaturelessCorridorIsAmbiguousAlongItsAxis) {
  // 26 m of corridor walls; the query sees 20 m of the same walls: every shift of up to 3 m along the axis fits.
  std::vector<slam::Point2> submap, query;
  addWall(submap, 0.0, 0.0, 26.0);
  addWall(submap, 2.5, 0.0, 26.0);
  addWall(query, -1.25, -10.0, 10.0);
  addWall(query, 1.25, -10.0, 10.0);
  const slam::CorrelationGrid grid(submap, 0.05, 0.07, 6, 0.03);
  slam::SearchWindow w;
  w.center = {13.0, 1.25, 0.0};
  w.xy = 2.0;
  w.theta = 0.1;
  const auto found = slam::branchAndBoundSearch(grid, query, w, 0.5);
  ASSERT_TRUE(found.has_value());
  EXPECT_NEAR(found->pose.y, 1.25, 0.03);
  const slam::Point2 at{found->pose.x, found->pose.y};
  EXPECT_TRUE(slam::branchAndBoundSearch(grid, query, w, 0.93 * found->score, &at, 0.6).has_value());
}

// With two threads the loop closure's steps run on their own thread, behind the filter (SlamRun): the trajectory,
// the closure table and a result read in the middle of the run are those of one thread, bit for bit.
TEST(LoopClosure, ItsOwnThreadGivesTheSerialResultBitForBit) {
  const sim::SimLog log = largeLoopLog();
  auto scans = std::make_shared<const std::vector<ScanRecord>>(log.records);
  struct Out {
    std::vector<TimedPose> mid, end;
    std::string closures;
  };
  const auto runWith = [&](int threads) {
    slam::SlamOptions o = testOptions();
    o.threads = threads;
    slam::SlamRun run(scans, o);
    run.filter().setInitialPose(toPose(log.truth.front()));
    Out out;
    while (!run.atEnd()) {
      run.step();
      if (run.scansFed() == scans->size() * 3 / 4) out.mid = run.trajectory();  // after the first closures
    }
    out.end = run.trajectory();
    out.closures = slam::closuresText(run.loopCloser()->closures(), run.loopCloser()->counts(), 0);
    return out;
  };
  const Out one = runWith(1), two = runWith(2);
  EXPECT_NE(one.closures.find("# closure "), std::string::npos);  // the run closed loops
  EXPECT_EQ(one.closures, two.closures);
  const auto expectSameBits = [](const std::vector<TimedPose>& a, const std::vector<TimedPose>& b) {
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(std::memcmp(&a[i].pose.x, &b[i].pose.x, sizeof(double)), 0) << i;
      ASSERT_EQ(std::memcmp(&a[i].pose.y, &b[i].pose.y, sizeof(double)), 0) << i;
      ASSERT_EQ(std::memcmp(&a[i].pose.phi, &b[i].pose.phi, sizeof(double)), 0) << i;
    }
  };
  expectSameBits(one.mid, two.mid);
  expectSameBits(one.end, two.end);
}

namespace {

// A 1 km ring of 2.5 m wide corridors, 300 m x 200 m, around a solid block; door recesses (1 m wide, 0.5 m deep)
// on both walls every 6 to 14 m at positions drawn from a fixed sequence, so that every stretch of 20 m differs.
sim::FloorPlan kilometreLoopPlan() {
  std::uint64_t state = 12345;
  const auto next = [&] {  // a fixed linear congruential sequence in [0, 1): the same plan on every platform
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  const auto recesses = [&](double from, double to) {
    std::vector<double> at;
    for (double x = from + 3.0 + 6.0 * next(); x < to - 4.0; x += 6.0 + 8.0 * next()) at.push_back(x);
    return at;
  };
  sim::FloorPlan p;
  const double W = 300, H = 200, w = 2.5;
  addRecessedWall(p, 0, 0, W, recesses(0, W), 1.0, -0.5);
  addRecessedWall(p, w, w, W - w, recesses(w, W - w), 1.0, 0.5);
  addRecessedWall(p, H, 0, W, recesses(0, W), 1.0, 0.5);
  addRecessedWall(p, H - w, w, W - w, recesses(w, W - w), 1.0, -0.5);
  // The west and east corridors: vertical walls, with recesses made by transposing horizontal ones.
  const auto vertical = [&](double x, double y0, double y1, double depth) {
    sim::FloorPlan h;
    addRecessedWall(h, x, y0, y1, recesses(y0, y1), 1.0, depth);
    for (const auto& s : h.walls) p.walls.push_back({s.y0, s.x0, s.y1, s.x1});
  };
  vertical(0, 0, H, -0.5);
  vertical(w, w, H - w, 0.5);
  vertical(W, 0, H, 0.5);
  vertical(W - w, w, H - w, -0.5);
  return p;
}

struct FedLoop {
  std::vector<slam::Pose2> drifted, closed;
  std::size_t back = 0;  ///< the node of the return nearest the start
  double drift_xy = 0.0, drift_th = 0.0, closed_xy = 0.0, closed_th = 0.0;
};

// The loop closure alone fed the true path of `log` with a heading bias of `bias` rad per metre (a filter that
// drifts), the way the filter feeds it; the return's error before and after.
FedLoop feedDrifting(const sim::SimLog& log, const slam::SlamOptions& o, double bias, slam::LoopClosureCounts* counts,
                     std::vector<slam::LoopClosureRecord>* closures) {
  slam::LoopCloser closer(o.loop_closure, o.motion);
  const auto& truth = log.truth;
  FedLoop r;
  slam::Pose2 filter = toPose(truth.front());
  for (std::size_t k = 0; k < truth.size(); ++k) {
    slam::Pose2 motion{0, 0, 0};
    if (k > 0) {
      motion = slam::relative(toPose(truth[k - 1]), toPose(truth[k]));
      motion.theta += bias * std::hypot(motion.x, motion.y);
      filter = slam::compose(filter, motion);
    }
    r.drifted.push_back(filter);
    const slam::PreparedScan ps = slam::prepareScan(log.records[k].scan, o.beams, o.resolution);
    closer.addScan(k, log.records[k].scan.timestamp, filter, motion, nullptr, ps);
  }
  r.closed = closer.finalPoses();
  if (counts) *counts = closer.counts();
  if (closures) *closures = closer.closures();
  // The return: after half the poses, the one nearest the start in the truth.
  double best = 1e18;
  for (std::size_t k = truth.size() / 2; k < truth.size(); ++k) {
    const double d = std::hypot(truth[k].x - truth[0].x, truth[k].y - truth[0].y);
    if (d < best) best = d, r.back = k;
  }
  const slam::Pose2 rt = slam::relative(toPose(truth[0]), toPose(truth[r.back]));
  const auto error = [&](const std::vector<slam::Pose2>& p, double& xy, double& th) {
    const slam::Pose2 re = slam::relative(p[0], p[r.back]);
    xy = std::hypot(re.x - rt.x, re.y - rt.y);
    th = std::abs(slam::wrapAngle(re.theta - rt.theta));
  };
  error(r.drifted, r.drift_xy, r.drift_th);
  error(r.closed, r.closed_xy, r.closed_th);
  return r;
}

// The look-alike corridors driven A east and back, B east and back, A east again (and back to the start with
// `back_again`).
sim::SimLog lookAlikeRun(bool back_again) {
  sim::SimOptions so;
  so.max_range = 10.0;
  so.scan_spacing = 0.3;
  so.seed = 9;
  const double pi = 3.14159265358979;
  std::vector<mrpt::math::TPose2D> path{{3, 1.25, 0},    {28.5, 1.25, 0}, {28.5, 1.25, pi}, {1.25, 1.25, pi},
                                        {1.25, 6.25, 0}, {28.5, 6.25, 0}, {28.5, 6.25, pi}, {1.25, 6.25, pi},
                                        {1.25, 1.25, 0}, {28.5, 1.25, 0}};
  if (back_again) path.insert(path.end(), {{28.5, 1.25, pi}, {1.25, 1.25, pi}});
  return sim::simulate(lookAlikePlan(), path, so);
}

}  // namespace

TEST(LoopClosure, AKilometreLoopThirtyMetresOffAtTheReturnClosesThroughTheGlobalSearch) {
  // Once round the 1 km ring counter-clockwise and 80 m on past the start; the filter's heading drifts by 0.4 mrad
  // per metre (20 degrees over the loop), so the return is tens of metres off: far beyond the windowed search's
  // 8 m. The place signatures must propose the start, agreeing matches accept it, and the loop closes.
  sim::SimOptions so;
  so.max_range = 10.0;
  so.beams = 91;
  so.scan_spacing = 0.5;
  so.seed = 21;
  const sim::SimLog log = sim::simulate(
      kilometreLoopPlan(),
      {{5, 1.25, 0}, {298.75, 1.25, 0}, {298.75, 198.75, 0}, {1.25, 198.75, 0}, {1.25, 1.25, 0}, {85, 1.25, 0}}, so);
  slam::SlamOptions o = testOptions();
  slam::LoopClosureCounts counts;
  std::vector<slam::LoopClosureRecord> closures;
  const FedLoop on = feedDrifting(log, o, 0.0004 * 0.87, &counts, &closures);
  std::printf("1 km loop: drift at the return %.2f m %.1f deg; closed %.3f m %.2f deg; global: searches %zu "
              "proposed %zu contradicted %zu accepted %zu dropped %zu\n",
              on.drift_xy, on.drift_th * 57.3, on.closed_xy, on.closed_th * 57.3, counts.global_searches,
              counts.global_proposed, counts.global_contradicted, counts.global_accepted, counts.global_dropped);
  EXPECT_GT(on.drift_xy, 25.0);
  EXPECT_GT(on.drift_th, 0.3);
  EXPECT_GT(counts.global_accepted, 2u);
  EXPECT_LT(on.closed_xy, 0.10);
  EXPECT_LT(on.closed_th, 0.01);
  // The summary's largest correction is the return's: the closure turns the newest pose back by the heading drift
  // and moves it by tens of metres (43 m here: it swings about a pivot between the place and the query, so not by
  // the whole 58 m), never by more than the drift.
  std::printf("largest correction %.2f m %.3f rad\n", counts.largest_correction_xy, counts.largest_correction_theta);
  EXPECT_GT(counts.largest_correction_xy, 0.5 * on.drift_xy);
  EXPECT_LT(counts.largest_correction_xy, 1.2 * on.drift_xy);
  EXPECT_NEAR(counts.largest_correction_theta, on.drift_th, 0.1);
  // Every global closure joins two poses that are truly at the same place.
  for (const auto& c : closures)
    if (c.global) {
      const auto& a = log.truth[c.scan_index];
      const auto& b = log.truth[c.submap_node];  // nodes are scans here: the loop closure is fed every scan
      EXPECT_LT(std::hypot(a.x - b.x, a.y - b.y), 3.0) << "global closure at scan " << c.scan_index;
    }
  // Without the global search the windowed one cannot reach the start: the loop stays open.
  o.loop_closure.global_search = false;
  const FedLoop off = feedDrifting(log, o, 0.0004 * 0.87, nullptr, nullptr);
  std::printf("1 km loop, windowed search alone: closed %.2f m\n", off.closed_xy);
  EXPECT_GT(off.closed_xy, 5.0);
}

TEST(LoopClosure, LookAlikeMatchesBesideTheTrajectoryAreProposedAndRefused) {
  // A east and back, B east and back, A east again, fed to the loop closure alone (no drift). B's places look like
  // A's, 5 m beside them: the global search proposes B-to-A matches, and the short trajectory between the two
  // corridors contradicts them. None may enter the graph; the real revisit of A does close.
  const sim::SimLog log = lookAlikeRun(false);
  slam::SlamOptions o = testOptions();
  slam::LoopClosureCounts counts;
  std::vector<slam::LoopClosureRecord> closures;
  const FedLoop r = feedDrifting(log, o, 0.0, &counts, &closures);
  std::size_t wrong = 0;  // global closures that join the two corridors
  for (const auto& c : closures)
    if (c.global && !c.rejected && (log.truth[c.scan_index].y > 4) != (log.truth[c.submap_node].y > 4)) ++wrong;
  double max_err = 0.0;
  for (std::size_t k = 0; k < r.closed.size(); ++k) {
    const slam::Pose2 e = slam::relative(r.closed[0], r.closed[k]);
    const slam::Pose2 t = slam::relative(toPose(log.truth[0]), toPose(log.truth[k]));
    max_err = std::max(max_err, std::hypot(e.x - t.x, e.y - t.y));
  }
  std::printf("look-alike, global: proposed %zu contradicted %zu beyond the drift bound %zu accepted %zu; closures "
              "%zu, across corridors %zu; max error %.3f m\n",
              counts.global_proposed, counts.global_contradicted, counts.global_beyond_bound, counts.global_accepted,
              closures.size(), wrong, max_err);
  EXPECT_GT(counts.global_contradicted + counts.global_beyond_bound, 0u);
  EXPECT_EQ(wrong, 0u);
  EXPECT_LT(max_err, 0.1);
}

TEST(LoopClosure, CandidatesBeyondTheDriftBoundAreSkippedWithoutChangingAnyClosure) {
  // The look-alike corridors of the test above, driven with a drifting heading: the global search proposes places
  // of both corridors in all headings. Skipping the candidates whose whole search window lies beyond the drift
  // bound (global_prejudge) must give the closures and poses of matching every candidate, bit for bit.
  const sim::SimLog log = lookAlikeRun(true);
  slam::SlamOptions o = testOptions();
  slam::LoopClosureCounts skip_counts, all_counts;
  std::vector<slam::LoopClosureRecord> skip_closures, all_closures;
  const FedLoop skip = feedDrifting(log, o, 0.002, &skip_counts, &skip_closures);
  o.loop_closure.global_prejudge = false;
  const FedLoop all = feedDrifting(log, o, 0.002, &all_counts, &all_closures);
  std::printf("drift bound: searches %zu, skipped %zu; proposed %zu / %zu, contradicted %zu / %zu, closures %zu / %zu\n",
              skip_counts.global_searches, skip_counts.global_beyond_bound, skip_counts.global_proposed,
              all_counts.global_proposed, skip_counts.global_contradicted, all_counts.global_contradicted,
              skip_closures.size(), all_closures.size());
  EXPECT_GT(skip_counts.global_beyond_bound, 0u);
  EXPECT_EQ(all_counts.global_beyond_bound, 0u);
  EXPECT_EQ(skip_counts.global_searches, all_counts.global_searches);
  EXPECT_LE(skip_counts.global_proposed, all_counts.global_proposed);
  EXPECT_EQ(skip_counts.global_accepted, all_counts.global_accepted);
  ASSERT_EQ(skip_closures.size(), all_closures.size());
  for (std::size_t k = 0; k < skip_closures.size(); ++k) {
    EXPECT_EQ(skip_closures[k].node, all_closures[k].node);
    EXPECT_EQ(skip_closures[k].submap_node, all_closures[k].submap_node);
    EXPECT_EQ(skip_closures[k].offset_xy, all_closures[k].offset_xy);
    EXPECT_EQ(skip_closures[k].global, all_closures[k].global);
  }
  ASSERT_EQ(skip.closed.size(), all.closed.size());
  for (std::size_t k = 0; k < skip.closed.size(); ++k) {
    EXPECT_EQ(skip.closed[k].x, all.closed[k].x);
    EXPECT_EQ(skip.closed[k].y, all.closed[k].y);
    EXPECT_EQ(skip.closed[k].theta, all.closed[k].theta);
  }
}
