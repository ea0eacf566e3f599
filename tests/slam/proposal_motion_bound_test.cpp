// The bound on how far a weakly supported scan-matching mode may lie from the odometry's prediction
// (proposal_max_motion_sigmas, proposal_weak_match_fraction): beyond it the match counts as failed and the particle
// takes the odometry proposal, as the informed proposal does when matching fails (Grisetti et al. 2007). A mode
// that few beams support and that the motion model puts many standard deviations away is a wrong mode (an open
// square outdoors: the campus log's filter turned 20-30 degrees per metre there); a mode most beams support is a
// correction of the odometry, whatever its size (FR079's odometry errs by more than six deviations on 1.4 % of its
// steps, and the matcher is right).
#include <gtest/gtest.h>

#include <cmath>

#include "common/slam_scene.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/prepared_scan.h"
#include "gridtopo/slam/proposal.h"
#include "gridtopo/slam/rbpf_slam.h"

using namespace gridtopo;
using namespace gridtopo::slam;

namespace {

/// A 4 m x 3 m room mapped from known poses; the scan is taken at `truth`, which lies `heading_error` rad (and a
/// few centimetres) away from the odometry's prediction prev ⊕ u.
struct RoomScene {
  GridMap map{0.05};
  sim::FloorPlan plan;
  SlamOptions o;
  PreparedScan scan;
  Pose2 prev{-0.25, 1.0, 0.0}, u{0.25, 0.0, 0.0}, truth;

  explicit RoomScene(double heading_error) {
    plan.addRectangle(-2, -0.5, 2, 2.5);
    sim::SimOptions so;
    so.range_sigma = 0.0;
    so.beams = 181;
    std::vector<mrpt::math::TPose2D> path;
    std::vector<double> times;
    for (int i = 0; i <= 20; ++i) {
      path.push_back({-1.0 + 0.1 * i, 1.0, 0.3 * i});
      times.push_back(static_cast<double>(i));
    }
    testing_scene::insertAtTruePoses(map, sim::simulatePath(plan, path, times, so), o.beams);
    truth = compose(prev, {u.x + 0.02, u.y - 0.01, u.theta + heading_error});
    sim::SimOptions s1 = so;
    s1.range_sigma = 0.005;
    scan = prepareScan(sim::simulatePath(plan, {{truth.x, truth.y, truth.theta}}, {0.0}, s1).records.at(0).scan,
                       o.beams, map.resolution());
  }

  ProposalPlan plan_with(double max_sigmas, double weak_fraction) {
    SlamOptions opt = o;
    opt.proposal.max_motion_sigmas = max_sigmas;
    opt.proposal.weak_match_fraction = weak_fraction;
    const OdometryMotionModel motion(opt.motion);
    return planProposal(map, prev, u, true, scan, opt, motion);
  }
};

}  // namespace

TEST(ProposalMotionBound, AModeFarFromThePredictionFailsOnlyWhenTheBoundAppliesToIt) {
  RoomScene s(0.3);
  const OdometryMotionModel motion(s.o.motion);
  const double sigma_theta = motion.sigmas(s.u, true).theta;
  ASSERT_GT(0.3 / sigma_theta, 5.0);  // the mode lies more than five deviations from the prediction

  // No bound (the default before this option): the matcher climbs to the true pose and the match is used.
  const ProposalPlan free = s.plan_with(0.0, 1.0);
  ASSERT_TRUE(free.matched);
  EXPECT_NEAR(wrapAngle(free.gaussian.mean.theta - s.truth.theta), 0.0, 0.02);
  EXPECT_NEAR(free.gaussian.mean.x, s.truth.x, 0.03);

  // Every match bounded at 3 deviations: this one is refused; the particle will take the odometry proposal.
  EXPECT_FALSE(s.plan_with(3.0, 1.0).matched);
  // Bounded only when fewer than half the beams find a correspondence: in a room every wall is in view, the
  // match is strong, and it stands.
  EXPECT_TRUE(s.plan_with(3.0, 0.5).matched);
  // A bound wider than the error leaves it alone.
  EXPECT_TRUE(s.plan_with(3.0 * 0.3 / sigma_theta, 1.0).matched);
}

TEST(ProposalMotionBound, AModeNearThePredictionIsUsedWhateverTheBound) {
  RoomScene s(0.01);
  const ProposalPlan bounded = s.plan_with(3.0, 1.0);
  ASSERT_TRUE(bounded.matched);
  const ProposalPlan free = s.plan_with(0.0, 1.0);
  EXPECT_EQ(bounded.gaussian.mean.x, free.gaussian.mean.x);
  EXPECT_EQ(bounded.gaussian.mean.theta, free.gaussian.mean.theta);
  EXPECT_EQ(bounded.log_weight_increment, free.log_weight_increment);
}

TEST(ProposalMotionBound, DefaultIniBoundsWeakMatchesAtThreeDeviations) {
  const SlamOptions o;
  EXPECT_EQ(o.proposal.max_motion_sigmas, 3.0);
  EXPECT_EQ(o.proposal.weak_match_fraction, 0.75);
}
