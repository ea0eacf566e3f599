// The proposal of Hähnel, Burgard, Fox, Thrun (IROS 2003), the baseline of Grisetti et al. 2007 (Sec. VII): the
// scan-matched motion replaces the odometry increment, the motion model is sampled around it, and the weight is
// p(z|m,x)^(1/gain) at the sample. On a simulated office with the robot 2 cm / 0.01 rad off its odometry.
#include <gtest/gtest.h>

#include <cmath>

#include "common/slam_scene.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/prepared_scan.h"
#include "gridtopo/slam/proposal.h"
#include "gridtopo/slam/rbpf_slam.h"
#include "gridtopo/slam/scan_matcher.h"
#include "gridtopo/slam/slam_options.h"

using namespace gridtopo;
using namespace gridtopo::slam;

namespace {
struct Scene {
  GridMap map{0.05};
  sim::FloorPlan plan = sim::FloorPlan::officeLoop();
  SlamOptions o;
  PreparedScan scan;
  Pose2 prev{6.0, 2.8, 0.02}, u{0.30, 0.0, 0.05};
  Pose2 truth;
  Scene() {
    o.proposal.type = ProposalType::Hahnel;
    sim::SimOptions so;
    so.range_sigma = 0.0;
    const std::vector<mrpt::math::TPose2D> wp = {{2, 6, -M_PI / 2}, {2, 2.8, 0}, {9, 2.8, 0}};
    const auto log = sim::simulate(plan, wp, so);
    testing_scene::insertAtTruePoses(map, log, o.beams);
    truth = compose(prev, {u.x + 0.02, u.y - 0.015, u.theta + 0.01});
    sim::SimOptions s1 = so;
    s1.range_sigma = 0.005;
    scan = testing_scene::scanAt(plan, truth, s1, o.beams, map.resolution());
  }
};
}  // namespace

TEST(HahnelProposal, SamplesTheMotionModelAroundTheScanMatchedPose) {
  Scene s;
  const OdometryMotionModel motion(s.o.motion);
  const ProposalPlan plan = planProposal(s.map, s.prev, s.u, true, s.scan, s.o, motion);
  ASSERT_TRUE(plan.matched);
  ASSERT_EQ(plan.type, ProposalType::Hahnel);
  const Pose2 matched = plan.gaussian.mean;
  EXPECT_LT(std::hypot(matched.x - s.truth.x, matched.y - s.truth.y), 0.01);  // the matcher finds the truth
  EXPECT_LT(std::abs(wrapAngle(matched.theta - s.truth.theta)), 0.005);
  const OdometryMotionModel::Sigmas sg = motion.sigmas(s.u, true);
  const int n = 4000;
  double mx = 0, my = 0, mt = 0, vx = 0, vt = 0;
  std::vector<Pose2> d(n);
  for (int i = 0; i < n; ++i) {
    Rng rng(7, 1, static_cast<std::uint64_t>(i), 1);
    Pose2 x;
    const double w = drawFromProposal(plan, s.map, s.prev, s.u, true, s.scan, s.o, motion, rng, x);
    // The weight is the softened likelihood at the sample itself.
    ASSERT_DOUBLE_EQ(w, scoreScan(s.map, x, s.scan, s.o.matcher).log_likelihood / s.o.likelihood_gain);
    d[i] = relative(s.prev, x);
    const Pose2 um = relative(s.prev, matched);
    d[i] = {d[i].x - um.x, d[i].y - um.y, wrapAngle(d[i].theta - um.theta)};
    mx += d[i].x / n;
    my += d[i].y / n;
    mt += d[i].theta / n;
  }
  for (const auto& e : d) {
    vx += (e.x - mx) * (e.x - mx) / n;
    vt += (e.theta - mt) * (e.theta - mt) / n;
  }
  // Centred on the scan-matched motion (not on the odometry, 2.5 cm away), with the motion model's spread.
  EXPECT_NEAR(mx, 0.0, 4 * sg.xy / std::sqrt(n));
  EXPECT_NEAR(my, 0.0, 4 * sg.xy / std::sqrt(n));
  EXPECT_NEAR(mt, 0.0, 4 * sg.theta / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(vx), sg.xy, 0.05 * sg.xy);
  EXPECT_NEAR(std::sqrt(vt), sg.theta, 0.05 * sg.theta);
}

TEST(HahnelProposal, FallsBackToTheOdometryProposalWhenMatchingFails) {
  Scene s;
  GridMap empty(0.05);  // nothing to match against
  const OdometryMotionModel motion(s.o.motion);
  const ProposalPlan plan = planProposal(empty, s.prev, s.u, true, s.scan, s.o, motion);
  EXPECT_FALSE(plan.matched);
  Rng a(3, 1, 0, 1), b(3, 1, 0, 1);
  Pose2 x, y;
  drawFromProposal(plan, empty, s.prev, s.u, true, s.scan, s.o, motion, a, x);
  const Pose2 expected = motion.sample(s.prev, s.u, b, true);
  EXPECT_EQ(x.x, expected.x);
  EXPECT_EQ(x.theta, expected.theta);
}

TEST(HahnelProposal, IsAnOptionWord) {
  EXPECT_EQ(proposalFromString("hahnel"), ProposalType::Hahnel);
  EXPECT_STREQ(toString(ProposalType::Hahnel), "hahnel");
  try {
    proposalFromString("greedy");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown proposal 'greedy' (expected informed, mode-only, hahnel, odometry)");
  }
}
