// A simulated building whose loop has a long featureless corridor, driven once around and a bit more under
// drifting odometry. Along the corridor the scans observe the heading and the lateral position but not the position
// along it: the informed proposal must follow the motion model in that direction and keep the particles spread
// along the corridor until the loop closes at its end, in the start area seen at the beginning of the log.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/odometry_error.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/rbpf_slam.h"
#include <mrpt/config/CConfigFile.h>
#include <opencv2/imgcodecs.hpp>

using namespace gridtopo;

namespace {

// Outer walls 0..44 x 0..14, central block 2..42 x 2..12: a loop of 2 m wide corridors. The south corridor
// (y 0..2, 44 m) has no feature at all; the laser (12 m) sees neither of its ends from x = 2.5 to x = 32, about
// 29 m. The north corridor has door recesses in both walls, the west and east corridors one recess each.
sim::FloorPlan corridorLoopPlan() {
  sim::FloorPlan p;
  // A horizontal wall at height y from x0 to x1 with recesses [a, a + w] of depth `depth` (signed: + goes to
  // larger y).
  auto wallWithRecesses = [&](double y, double x0, double x1, std::vector<double> starts, double w, double depth) {
    double x = x0;
    for (double a : starts) {
      p.walls.push_back({x, y, a, y});
      p.walls.push_back({a, y, a, y + depth});
      p.walls.push_back({a, y + depth, a + w, y + depth});
      p.walls.push_back({a + w, y + depth, a + w, y});
      x = a + w;
    }
    p.walls.push_back({x, y, x1, y});
  };
  // Outer walls: south and west/east plain, north with door recesses (0.9 m wide, 0.4 m deep).
  p.walls.push_back({0, 0, 44, 0});
  p.walls.push_back({44, 0, 44, 7});
  p.walls.push_back({44, 7, 44.5, 7});  // east recess 7..8
  p.walls.push_back({44.5, 7, 44.5, 8});
  p.walls.push_back({44.5, 8, 44, 8});
  p.walls.push_back({44, 8, 44, 14});
  wallWithRecesses(14, 0, 44, {5, 11, 19, 24, 31, 37}, 0.9, 0.4);
  p.walls.push_back({0, 14, 0, 6});
  p.walls.push_back({0, 6, -0.5, 6});  // west recess 5..6
  p.walls.push_back({-0.5, 6, -0.5, 5});
  p.walls.push_back({-0.5, 5, 0, 5});
  p.walls.push_back({0, 5, 0, 0});
  // Central block: south and west/east plain, north with recesses at other places than the outer wall's.
  p.walls.push_back({2, 2, 42, 2});
  p.walls.push_back({42, 2, 42, 12});
  wallWithRecesses(12, 2, 42, {8, 15, 21.5, 28, 34}, 0.9, -0.4);
  p.walls.push_back({2, 12, 2, 2});
  return p;
}

// Start near the east end of the long corridor heading east (the laser sees the end wall and the opening of the
// east corridor), go round counter-clockwise (north, west along the north corridor, south, then the whole long
// corridor east), so that the loop closes at the end of the featureless stretch, and drive on up the east corridor.
constexpr double kStartX = 34.0;
std::vector<mrpt::math::TPose2D> corridorLoopWaypoints() {
  return {{kStartX, 1, 0}, {43, 1, 0}, {43, 13, 0}, {1, 13, 0}, {1, 1, 0}, {43, 1, 0}, {43, 8, 0}};
}

struct Result {
  double closure_xy = 0, closure_th = 0;  ///< max error against the truth from the closure to the end
  double closure_mean_th = 0;             ///< mean heading error from the closure to the end
  std::size_t closure_n = 0;
  double loop_xy = 0, loop_th = 0;    ///< max loop-consistency error (first pass vs closure pass)
  double odo_closure_xy = 0;          ///< odometry's error against the truth at the closure
  double odo_loop_xy = 0;             ///< odometry's loop-consistency error
  double final_xy = 0, final_th = 0;  ///< the last pose
  double max_xy = 0;                  ///< whole trajectory against the truth
  double spread_x = 0;                ///< std-dev of the particles' x, 26 m into the featureless stretch
  double lag_x = 0;                   ///< the path's x minus the true x there (negative: behind)
  std::size_t scans = 0, steps = 0, closure_index = 0;
  double seconds = 0;
};

slam::Pose2 toPose(const mrpt::math::TPose2D& p) { return {p.x, p.y, p.phi}; }

// Simulates the log (sim and filter seeded with `seed`; odometry translation scaled by 1 + scale_error) and runs
// the filter with `base`.
Result runCorridorLoop(std::uint64_t seed, double scale_error, const slam::SlamOptions& base,
                       const char* picture = nullptr) {
  const auto plan = corridorLoopPlan();
  sim::SimOptions so;
  so.max_range = 12.0;    // the corridor's ends are out of range from its middle
  so.scan_spacing = 0.3;  // > linear_update even with the odometry 2 % short: every scan is processed
  so.odo_sigma_xy = 0.01;
  so.odo_sigma_theta = 0.02;
  so.odo_sigma_theta_per_m = 0.01;
  so.odo_drift_theta = 0.004;  // rad per m: about 0.5 rad over the 124 m
  so.seed = seed;
  auto log = sim::simulate(plan, corridorLoopWaypoints(), so);
  testing_scene::scaleOdometry(log, scale_error);

  const auto& truth = log.truth;
  // On the second pass along the long corridor: `mid`, 26 m into the featureless stretch (the end wall is 16 m
  // away), and the closure `k`, the first pose east of the start.
  std::size_t mid = 0;
  while (mid < truth.size() && !(truth[mid].x < 2)) ++mid;  // the west corridor
  while (mid < truth.size() && !(truth[mid].x >= 28)) ++mid;
  std::size_t k = mid;
  while (k < truth.size() && !(truth[k].x >= kStartX)) ++k;

  slam::SlamOptions o = base;
  o.seed = seed;
  Result res;
  res.closure_index = k;
  const auto t0 = std::chrono::steady_clock::now();
  slam::RbpfSlam slam(o);
  for (std::size_t i = 0; i < log.records.size(); ++i) {
    slam.processScan(log.records[i]);
    if (i != mid) continue;
    double mean = 0, var = 0;
    for (const auto& p : slam.particles()) mean += p.pose.x;
    mean /= static_cast<double>(slam.particles().size());
    for (const auto& p : slam.particles()) var += (p.pose.x - mean) * (p.pose.x - mean);
    res.spread_x = std::sqrt(var / static_cast<double>(slam.particles().size()));
  }
  const auto traj = slam.trajectory();
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.scans = traj.size();
  res.steps = slam.stepsProcessed();
  if (mid < traj.size()) res.lag_x = traj[mid].pose.x - truth[mid].x;
  // The first pass through the same places: the start of the log up to the north corridor.
  std::size_t first_pass = 0;
  while (first_pass < truth.size() && !(truth[first_pass].y > 12.5)) ++first_pass;
  for (std::size_t i = 0; i < traj.size(); ++i) {
    const double dxy = std::hypot(traj[i].pose.x - truth[i].x, traj[i].pose.y - truth[i].y);
    const double dth = std::abs(slam::wrapAngle(traj[i].pose.phi - truth[i].phi));
    res.max_xy = std::max(res.max_xy, dxy);
    if (i < k) continue;
    res.closure_xy = std::max(res.closure_xy, dxy);
    res.closure_th = std::max(res.closure_th, dth);
    res.closure_mean_th += dth;
    ++res.closure_n;
    // Loop consistency: the pose relative to the first-pass pose nearest in the truth (same heading), against
    // the true relative pose. A doubled corridor shows up here whatever the map's global error.
    std::size_t j = 0;
    double best = 1e9;
    for (std::size_t c = 0; c < first_pass; ++c) {
      if (std::abs(slam::wrapAngle(truth[c].phi - truth[i].phi)) > 0.2) continue;
      const double d = std::hypot(truth[c].x - truth[i].x, truth[c].y - truth[i].y);
      if (d < best) best = d, j = c;
    }
    if (best > 0.5) continue;
    const slam::Pose2 rt = slam::relative(toPose(truth[j]), toPose(truth[i]));
    const slam::Pose2 re = slam::relative(toPose(traj[j].pose), toPose(traj[i].pose));
    const slam::Pose2 ro = slam::relative(toPose(log.records[j].odometry), toPose(log.records[i].odometry));
    res.loop_xy = std::max(res.loop_xy, std::hypot(re.x - rt.x, re.y - rt.y));
    res.loop_th = std::max(res.loop_th, std::abs(slam::wrapAngle(re.theta - rt.theta)));
    res.odo_loop_xy = std::max(res.odo_loop_xy, std::hypot(ro.x - rt.x, ro.y - rt.y));
  }
  if (res.closure_n) res.closure_mean_th /= res.closure_n;
  if (k < traj.size()) {
    const auto& od = log.records[k].odometry;
    res.odo_closure_xy = std::hypot(od.x - truth[k].x, od.y - truth[k].y);
    res.final_xy = std::hypot(traj.back().pose.x - truth.back().x, traj.back().pose.y - truth.back().y);
    res.final_th = std::abs(slam::wrapAngle(traj.back().pose.phi - truth.back().phi));
  }
  if (std::getenv("GRIDTOPO_TEST_VERBOSE"))
    for (std::size_t i = 0; i < traj.size(); i += 20)
      std::printf("%zu est %.3f %.3f %.4f truth %.3f %.3f %.4f odometry %.3f %.3f %.4f\n", i, traj[i].pose.x,
                  traj[i].pose.y, traj[i].pose.phi, truth[i].x, truth[i].y, truth[i].phi, log.records[i].odometry.x,
                  log.records[i].odometry.y, log.records[i].odometry.phi);
  if (const char* dir = std::getenv("GRIDTOPO_TEST_PICTURES"); dir && picture)
    cv::imwrite(std::string(dir) + "/" + picture,
                slam::renderMap(slam::toOccupancyGrid(slam.bestParticle().map), traj));
  std::printf(
      "seed %llu, scale error %+.2f: 26 m into the corridor: particles' spread %.3f m, path %+.3f m along; "
      "after the closure: max %.3f m %.2f deg (mean %.2f) against the truth, "
      "loop consistency max %.3f m %.2f deg, "
      "final %.3f m %.2f deg; whole path max %.3f m; odometry at the closure %.2f m, loop consistency %.2f m; "
      "%zu scans, %zu steps, closure at scan %zu; %.1f s\n",
      static_cast<unsigned long long>(seed), scale_error, res.spread_x, res.lag_x, res.closure_xy,
      res.closure_th * 180 / M_PI, res.closure_mean_th * 180 / M_PI, res.loop_xy, res.loop_th * 180 / M_PI,
      res.final_xy, res.final_th * 180 / M_PI, res.max_xy, res.odo_closure_xy, res.odo_loop_xy, res.scans, res.steps,
      res.closure_index, res.seconds);
  return res;
}

// The default options, two threads; GRIDTOPO_TEST_INI names an INI whose [slam] section overrides them (to check
// other settings by hand).
slam::SlamOptions corridorOptions() {
  slam::SlamOptions o;
  if (const char* ini = std::getenv("GRIDTOPO_TEST_INI")) {
    mrpt::config::CConfigFile cfg(ini);
    o.loadFromConfigFile(cfg, "slam");
  }
  o.threads = 2;
  return o;
}

// The proposal before the curvature fit: the paper's weighted moments on the old 0.01 m / 0.005 rad grid, every
// particle's mode search starting from the odometry prediction.
slam::SlamOptions previousProposal() {
  slam::SlamOptions o = corridorOptions();
  o.proposal.fit = slam::ProposalFit::Moments;
  o.proposal.start_spread = 0;
  o.proposal.delta_xy = 0.01;
  o.proposal.delta_theta = 0.005;
  return o;
}

// The seed of the simulation and of the filter; GRIDTOPO_TEST_SEED overrides it (to check other seeds by hand).
std::uint64_t testSeed(std::uint64_t seed = 1) {
  const char* s = std::getenv("GRIDTOPO_TEST_SEED");
  return s ? std::strtoull(s, nullptr, 10) : seed;
}

}  // namespace

// Values seen (30 particles, 2 threads; seeds 1-6 with the odometry 2 % long, exact and 2 % short, 18 runs, with
// match_occupied_log_odds = 0), 26 m into the featureless stretch: the particles' spread along the corridor is
// 0.20-0.84 m with the new proposal and 0.011-0.20 m (15 of 18 below 0.07 m) with the previous one; this seed with
// the default options: 0.589 m and 0.140 m. The odometry is 4.5-6.7 m off at the closure. About 2 s.
TEST(CorridorLoop, ProposalFollowsTheMotionModelAlongTheCorridor) {
  const Result r = runCorridorLoop(testSeed(), 0.02, corridorOptions(), "corridor_loop.png");
  EXPECT_GT(r.odo_closure_xy, 3.0);  // dead reckoning is far off at the closure
  EXPECT_GT(r.spread_x, 0.15);       // the scans do not observe x here: the motion model's spread remains
}

// The previous proposal never closes this loop: 2.4-3.9 m off after the closure (max over the poses from the
// closure to the end, relative to the first pass) in all 18 runs with 30 particles and 12 with 60 (threshold 0);
// 2.96 m here with the default options.
// Its particles collapse along the corridor (above) and all fall behind the truth (2.2-2.9 m after 26 m), so the
// corridor's end is mapped twice. About 2 s.
TEST(CorridorLoop, PreviousProposalDoesNotClose) {
  const Result r = runCorridorLoop(testSeed(), 0.02, previousProposal(), "corridor_loop_previous.png");
  EXPECT_GT(r.odo_closure_xy, 3.0);
  EXPECT_GT(r.loop_xy, 1.0);
}

// The loop closes at the end of the featureless stretch. Values seen (30 particles, odometry 2 % long, seeds 1-3):
// 26 m into the stretch the path is -0.16, -0.28, -0.01 m along the corridor from the truth; after the closure the
// pose is at most 0.14, 0.11, 0.25 m and 0.55, 0.44, 1.95 degrees (mean 0.15, 0.11, 1.52) off the truth, 0.13, 0.11,
// 0.07 m off the first pass; final 0.05, 0.08, 0.21 m, 0.02, 0.04, 1.43 degrees. With match_occupied_log_odds = 0
// (before it became -2) the path fell 2.0-2.1 m behind on seeds 1 and 3 and the corridor's end was mapped twice
// (2.4 / 2.5 m after the closure): the cells of the walls, crossed by many grazing free rays, fell below log-odds 0
// while holding hit means, and the end points ahead of the true pose lost their correspondences
// (corridor_likelihood_test; doc/slam.md "Long corridors"). Not solved for every seed: on seeds 4-8 (checked by hand,
// GRIDTOPO_TEST_SEED with the test above) the default closes 3 of 5 (seeds 4 and 7 fall 2.4-2.8 m behind), threshold
// 0 closes 1 (2 more within 0.5-0.7 m). Nearby settings flip single seeds (proposal_min_curvature 1 fails seeds 1 and 2,
// 0 fails seed 2, 0.5 passes), so this test guards the three seeds, not the class. Seeds 1-20 (2026-12-06, main
// ae5418c, GRIDTOPO_TEST_SEED=N on this test): 17 close; 4, 7 and 14 fall 1.9-2.7 m behind. About 7 s.
TEST(CorridorLoop, ClosesAfterTheFeaturelessCorridor) {
  // Seeds 1-3, or the one GRIDTOPO_TEST_SEED names (other seeds by hand: the class, not these three).
  const std::uint64_t first = std::getenv("GRIDTOPO_TEST_SEED") ? testSeed() : 1, last = first == 1 ? 3 : first;
  for (std::uint64_t seed = first; seed <= last; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Result r = runCorridorLoop(seed, 0.02, corridorOptions());
    EXPECT_GT(r.odo_loop_xy, 5.0);
    EXPECT_GT(r.lag_x, -0.6);       // no fall behind the truth along the corridor
    EXPECT_LT(r.closure_xy, 0.4);   // against the truth, from the closure to the end
    EXPECT_LT(r.loop_xy, 0.4);      // against the first pass: no doubled corridor end
    EXPECT_LT(r.closure_mean_th, 2.0 * M_PI / 180);
    EXPECT_LT(r.final_th, 2.0 * M_PI / 180);
  }
}
