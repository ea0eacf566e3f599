// The relations metric on synthetic trajectories with known answers.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/eval/relations_metric.h"

using namespace gridtopo::eval;
using gridtopo::TimedPose;
using mrpt::math::TPose2D;

namespace {

/// A smooth ground-truth trajectory sampled every 0.2 s (like a laser at 5 Hz).
std::vector<TimedPose> groundTruth(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> dv(0.0, 0.05), dw(0.0, 0.1);
  std::vector<TimedPose> out;
  TPose2D p{1.0, -2.0, 0.3};
  double v = 0.4, w = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    out.push_back({1000.0 + 0.2 * static_cast<double>(i), p});
    v = std::clamp(v + dv(rng), 0.0, 0.8);
    w = std::clamp(w + dw(rng), -0.8, 0.8);
    p = p + TPose2D(v * 0.2, 0.0, w * 0.2);
    p.phi = mrpt::math::wrapToPi(p.phi);
  }
  return out;
}

/// Relations between random pairs (some with t2 < t1, some far apart like loop closures).
std::vector<Relation> relationsOf(const std::vector<TimedPose>& gt, std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, gt.size() - 1);
  std::vector<Relation> out;
  for (std::size_t k = 0; k < n; ++k) {
    const auto& a = gt[pick(rng)];
    const auto& b = gt[pick(rng)];
    Relation r;
    r.t1 = a.timestamp;
    r.t2 = b.timestamp;
    r.delta = b.pose - a.pose;
    r.line = k + 1;
    out.push_back(r);
  }
  return out;
}

}  // namespace

TEST(RelationsMetric, PerfectShuffledTrajectoryScoresZero) {
  auto gt = groundTruth(500, 1);
  const auto rel = relationsOf(gt, 300, 2);
  std::mt19937 rng(3);
  std::shuffle(gt.begin(), gt.end(), rng);  // trajectories need not be sorted
  const auto r = evaluateRelations(gt, rel, nullptr);
  EXPECT_EQ(r.translational.count, 300u);
  EXPECT_LT(r.translational.max, 1e-9);
  EXPECT_LT(r.rotational.max, 1e-7);
  EXPECT_EQ(r.endpoints_direct, 600u);
  EXPECT_EQ(r.max_gap, 0.0);
}

TEST(RelationsMetric, RigidlyMovedTrajectoryScoresZero) {
  const auto gt = groundTruth(300, 4);
  const auto rel = relationsOf(gt, 200, 5);
  std::vector<TimedPose> moved = gt;
  const TPose2D T{12.0, -7.0, 2.0};
  for (auto& p : moved) p.pose = T + p.pose;  // relations are invariant to the choice of the world frame
  const auto r = evaluateRelations(moved, rel, nullptr);
  EXPECT_LT(r.translational.max, 1e-9);
  EXPECT_LT(r.rotational.max, 1e-7);
}

TEST(RelationsMetric, ScaledTrajectoryGivesKnownTranslationalError) {
  const auto gt = groundTruth(300, 6);
  const auto rel = relationsOf(gt, 200, 7);
  std::vector<TimedPose> scaled = gt;
  const double s = 0.05;
  for (auto& p : scaled) p.pose = {p.pose.x * (1 + s), p.pose.y * (1 + s), p.pose.phi};
  const auto r = evaluateRelations(scaled, rel, nullptr);
  std::vector<double> expected;
  for (const auto& x : rel) expected.push_back(s * std::hypot(x.delta.x, x.delta.y));
  const auto e = ErrorStats::of(expected);
  EXPECT_NEAR(r.translational.mean, e.mean, 1e-9);
  EXPECT_NEAR(r.translational.std, e.std, 1e-9);
  EXPECT_NEAR(r.translational.max, e.max, 1e-9);
  EXPECT_LT(r.rotational.max, 1e-7);
  for (std::size_t i = 0; i < rel.size(); ++i) EXPECT_NEAR(r.errors[i].translational, expected[i], 1e-9);
}

TEST(RelationsMetric, KnownErrorsOnOnePose) {
  // Three poses on a line; the estimate of the middle one is off by (0.1, -0.2, 5°).
  std::vector<TimedPose> gt = {{0.0, {0, 0, 0}}, {1.0, {1, 0, 0}}, {2.0, {2, 0, 0}}};
  std::vector<Relation> rel(3);
  rel[0] = {0.0, 1.0, gt[1].pose - gt[0].pose, 1};
  rel[1] = {2.0, 1.0, gt[1].pose - gt[2].pose, 2};  // t2 < t1
  rel[2] = {0.0, 2.0, gt[2].pose - gt[0].pose, 3};
  auto est = gt;
  const double a = 5.0 * M_PI / 180.0;
  est[1].pose = {1.1, -0.2, a};
  const auto r = evaluateRelations(est, rel, nullptr);
  EXPECT_NEAR(r.errors[0].translational, std::hypot(0.1, 0.2), 1e-12);
  EXPECT_NEAR(r.errors[0].rotational, a, 1e-12);
  // Seen from pose 2 (facing +x at (2,0)): the estimate is at (-0.9, -0.2) instead of (-1, 0).
  EXPECT_NEAR(r.errors[1].translational, std::hypot(0.1, 0.2), 1e-12);
  EXPECT_NEAR(r.errors[1].rotational, a, 1e-12);
  EXPECT_NEAR(r.errors[2].translational, 0.0, 1e-12);
  EXPECT_EQ(r.rotational.count, 3u);
  EXPECT_NEAR(r.rotational.mean, 2.0 / 3.0 * 5.0, 1e-9);
  EXPECT_NEAR(r.rotational.std, std::sqrt((2 * std::pow(5.0 - 10.0 / 3, 2) + std::pow(10.0 / 3, 2)) / 2), 1e-9);
  EXPECT_NEAR(r.rotational_squared.mean, 2.0 / 3.0 * 25.0, 1e-9);
  EXPECT_NEAR(r.translational_squared.max, 0.05, 1e-12);
  EXPECT_NEAR(r.rotational.min, 0.0, 1e-12);
  EXPECT_NEAR(r.rotational.max, 5.0, 1e-9);
}

TEST(RelationsMetric, RotationalErrorWrapsAroundPi) {
  std::vector<TimedPose> est = {{0.0, {0, 0, 3.1}}, {1.0, {0, 0, -3.1}}};
  std::vector<Relation> rel = {{0.0, 1.0, {0, 0, 0.0}, 1}};
  const auto r = evaluateRelations(est, rel, nullptr);
  EXPECT_NEAR(r.errors[0].rotational, 2 * M_PI - 6.2, 1e-12);
}

TEST(RelationsMetric, GapsAreCorrectedByOdometryBeyondMaxGapOnly) {
  const auto gt = groundTruth(400, 8);
  const auto rel = relationsOf(gt, 300, 9);
  // Odometry = ground truth seen from a drifting, rotated frame: its relative motions are exact.
  std::vector<TimedPose> odo = gt;
  for (auto& p : odo) p.pose = TPose2D(-3, 4, 1.0) + p.pose;
  const OdometryTrack track(odo);
  // The estimate has only every 7th pose, stamped 0.05 s late: within max_gap it is used as is.
  std::vector<TimedPose> sparse;
  for (std::size_t i = 0; i < gt.size(); i += 7) sparse.push_back({gt[i].timestamp + 0.05, gt[i].pose});
  const auto r = evaluateRelations(sparse, rel, &track);
  EXPECT_GT(r.endpoints_corrected, 400u);
  EXPECT_GT(r.endpoints_direct, 50u);
  EXPECT_EQ(r.endpoints_uncorrected, 0u);
  // Corrected endpoints: odometry at the estimate's time (t + 0.05) is the reading nearest to it, i.e. the
  // pose at t itself, so the correction is exact and the error is zero.
  EXPECT_LT(r.translational.max, 1e-9);
  EXPECT_LT(r.rotational.max, 1e-7);
  // Without odometry the far endpoints stay uncorrected and errors appear.
  const auto u = evaluateRelations(sparse, rel, nullptr);
  EXPECT_EQ(u.endpoints_uncorrected, r.endpoints_corrected);
  EXPECT_GT(u.translational.mean, 0.05);
  // With max_gap = 0 every endpoint is corrected (the estimate is 0.05 s off everywhere).
  RelationsMetricOptions o;
  o.max_time_gap = 0.0;
  const auto z = evaluateRelations(sparse, rel, &track, o);
  EXPECT_EQ(z.endpoints_direct, 0u);
  EXPECT_LT(z.translational.max, 1e-9);
}

TEST(RelationsMetric, InterpolatedOdometry) {
  // Odometry moving at 1 m/s along x, sampled at 1 Hz; estimate at t=0 only.
  std::vector<TimedPose> odo;
  for (int i = 0; i <= 10; ++i) odo.push_back({double(i), {double(i), 0, 0}});
  const OdometryTrack track(odo);
  EXPECT_EQ(track.nearest(2.5).timestamp, 2.0);  // tie: the earlier reading
  EXPECT_EQ(track.nearest(2.51).timestamp, 3.0);
  EXPECT_NEAR(track.interpolate(2.25).x, 2.25, 1e-12);
  EXPECT_NEAR(track.interpolate(-5).x, 0.0, 1e-12);
  EXPECT_NEAR(track.interpolate(50).x, 10.0, 1e-12);
  // Theta interpolates along the shorter arc.
  const OdometryTrack turn({{0.0, {0, 0, 3.0}}, {1.0, {0, 0, -3.0}}});
  EXPECT_NEAR(std::abs(turn.interpolate(0.5).phi), M_PI, 1e-9);

  std::vector<TimedPose> est = {{0.0, {0, 0, 0}}};
  std::vector<Relation> rel = {{0.0, 4.4, {4.4, 0, 0}, 1}};
  RelationsMetricOptions o;
  const auto nearest = evaluateRelations(est, rel, &track, o);
  EXPECT_NEAR(nearest.errors[0].translational, 0.4, 1e-12);  // odometry at 4.4 = reading at 4
  o.interpolate_odometry = true;
  const auto interp = evaluateRelations(est, rel, &track, o);
  EXPECT_NEAR(interp.errors[0].translational, 0.0, 1e-12);
}

TEST(RelationsMetric, NearestPoseTieAndDuplicates) {
  // Poses at 0 and 1 (twice, the first in file order wins); t = 0.5 is a tie -> the earlier pose.
  std::vector<TimedPose> est = {{1.0, {5, 0, 0}}, {0.0, {1, 0, 0}}, {1.0, {9, 0, 0}}};
  RelationsMetricOptions o;
  o.max_time_gap = 10.0;
  const TrajectoryLookup look(est, nullptr, o);
  EXPECT_EQ(look.poseAt(0.5).pose.x, 1.0);
  EXPECT_EQ(look.poseAt(0.51).pose.x, 5.0);
  EXPECT_EQ(look.poseAt(1.0).pose.x, 5.0);
  EXPECT_EQ(look.poseAt(7.0).pose.x, 5.0);
  EXPECT_NEAR(look.poseAt(7.0).gap, 6.0, 1e-12);
}

namespace {
// Four estimated poses on a line; three relations with known errors: two local ones (|t2 - t1| = 10 s; the second
// with t2 < t1) of 0.1 m / 1 deg and 0.3 m / 3 deg, one revisit (100 s apart: the robot is back at its start) of
// 2.0 m / 20 deg.
struct SplitCase {
  std::vector<TimedPose> est = {{0.0, {0, 0, 0}}, {10.0, {1, 0, 0}}, {20.0, {2, 0, 0}}, {100.0, {0, 0, 0}}};
  std::vector<Relation> rel;
  SplitCase() {
    const double deg = M_PI / 180.0;
    rel.push_back({0.0, 10.0, {1.1, 0, 1 * deg}, 1});     // estimated delta (1, 0, 0): 0.1 m, 1 deg
    rel.push_back({20.0, 10.0, {-1.3, 0, -3 * deg}, 2});  // estimated delta (-1, 0, 0): 0.3 m, 3 deg
    rel.push_back({0.0, 100.0, {0, 2.0, 20 * deg}, 3});   // estimated delta (0, 0, 0): 2.0 m, 20 deg
  }
};
}  // namespace

TEST(RelationsMetric, SplitsLocalAndRevisitRelationsByTheirTimeSpan) {
  const SplitCase c;
  const auto r = evaluateRelations(c.est, c.rel, nullptr);  // default span: 50 s
  EXPECT_EQ(r.revisit_span, 50.0);
  ASSERT_EQ(r.local.translational.count, 2u);
  EXPECT_EQ(r.local.rotational.count, 2u);
  EXPECT_NEAR(r.local.translational.mean, 0.2, 1e-12);
  EXPECT_NEAR(r.local.translational.std, std::sqrt(0.02), 1e-12);  // sample std of {0.1, 0.3}
  EXPECT_NEAR(r.local.translational.min, 0.1, 1e-12);
  EXPECT_NEAR(r.local.translational.max, 0.3, 1e-12);
  EXPECT_NEAR(r.local.rotational.mean, 2.0, 1e-9);  // deg
  EXPECT_NEAR(r.local.rotational.max, 3.0, 1e-9);
  ASSERT_EQ(r.revisit.translational.count, 1u);
  EXPECT_EQ(r.revisit.rotational.count, 1u);
  EXPECT_NEAR(r.revisit.translational.mean, 2.0, 1e-12);
  EXPECT_EQ(r.revisit.translational.std, 0.0);
  EXPECT_NEAR(r.revisit.rotational.mean, 20.0, 1e-9);
  // The totals are over all three, as before.
  EXPECT_EQ(r.translational.count, 3u);
  EXPECT_NEAR(r.translational.mean, 0.8, 1e-12);
  EXPECT_NEAR(r.rotational.mean, 8.0, 1e-9);
}

TEST(RelationsMetric, RevisitSpanMovesRelationsBetweenLocalAndRevisit) {
  const SplitCase c;
  RelationsMetricOptions o;
  const auto totals = evaluateRelations(c.est, c.rel, nullptr, o);
  o.revisit_span = 5.0;  // every relation is longer: all revisits
  const auto all_revisits = evaluateRelations(c.est, c.rel, nullptr, o);
  EXPECT_EQ(all_revisits.revisit_span, 5.0);
  EXPECT_EQ(all_revisits.local.translational.count, 0u);
  EXPECT_EQ(all_revisits.local.translational.mean, 0.0);
  EXPECT_EQ(all_revisits.revisit.translational.count, 3u);
  EXPECT_NEAR(all_revisits.revisit.translational.mean, 0.8, 1e-12);
  EXPECT_NEAR(all_revisits.revisit.rotational.mean, 8.0, 1e-9);
  o.revisit_span = 100.0;  // |t2 - t1| = 100 is not more than the span: local (the bound belongs to local)
  const auto all_local = evaluateRelations(c.est, c.rel, nullptr, o);
  EXPECT_EQ(all_local.local.translational.count, 3u);
  EXPECT_NEAR(all_local.local.translational.mean, 0.8, 1e-12);
  EXPECT_EQ(all_local.revisit.translational.count, 0u);
  o.revisit_span = 99.999;
  const auto just_below = evaluateRelations(c.est, c.rel, nullptr, o);
  EXPECT_EQ(just_below.local.translational.count, 2u);
  EXPECT_EQ(just_below.revisit.translational.count, 1u);
  // The span changes the split only: totals and per-relation errors stay the same.
  for (const auto* x : {&all_revisits, &all_local, &just_below}) {
    EXPECT_EQ(x->translational.mean, totals.translational.mean);
    EXPECT_EQ(x->rotational_squared.mean, totals.rotational_squared.mean);
    ASSERT_EQ(x->errors.size(), totals.errors.size());
    for (std::size_t i = 0; i < x->errors.size(); ++i)
      EXPECT_EQ(x->errors[i].translational, totals.errors[i].translational);
  }
}

TEST(RelationsMetric, RevisitSpanFromIniMustBePositive) {
  RelationsMetricOptions o;
  EXPECT_EQ(o.revisit_span, 50.0);
  const auto load = [](RelationsMetricOptions& x, const std::string& text) {
    x.loadFromConfigFile(mrpt::config::CConfigFileMemory("[relations_metric]\n" + text), "relations_metric");
  };
  load(o, "revisit_span = 12.5\n");
  EXPECT_EQ(o.revisit_span, 12.5);
  load(o, "max_time_gap = 0.2\n");
  EXPECT_EQ(o.revisit_span, 12.5);  // a missing key keeps its value
  for (const char* bad : {"0", "-3", "abc"}) {
    try {
      RelationsMetricOptions b;
      load(b, std::string("revisit_span = ") + bad + "\n");
      ADD_FAILURE() << "revisit_span = " << bad << " accepted";
    } catch (const gridtopo::InputError& e) {
      EXPECT_EQ(e.field(), "[relations_metric] revisit_span") << e.what();
    }
  }
}

TEST(RelationsMetric, EmptyInputsAreErrors) {
  std::vector<Relation> rel = {{0.0, 1.0, {1, 0, 0}, 1}};
  EXPECT_THROW(evaluateRelations({}, rel, nullptr), std::invalid_argument);
  EXPECT_THROW(evaluateRelations({{0.0, {0, 0, 0}}}, {}, nullptr), std::invalid_argument);
}

TEST(RelationsMetric, StatsUseTheSampleStd) {
  const auto s = ErrorStats::of({1.0, 2.0, 3.0, 4.0});
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(5.0 / 3.0));
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 4.0);
  EXPECT_EQ(ErrorStats::of({2.0}).std, 0.0);
}

TEST(RelationsMetric, OptionsFromIni) {
  mrpt::config::CConfigFileMemory ini(
      "[relations_metric]\nmax_time_gap = 0.25\ninterpolate_odometry = true\ninterpolate_estimate = yes\nodometry = laser\n");
  RelationsMetricOptions o;
  o.loadFromConfigFile(ini, "relations_metric");
  EXPECT_EQ(o.max_time_gap, 0.25);
  EXPECT_TRUE(o.interpolate_odometry);
  EXPECT_TRUE(o.interpolate_estimate);
  EXPECT_EQ(o.odometry, OdometrySource::LaserLines);
  std::ostringstream dump;
  o.dumpToTextStream(dump);
  EXPECT_NE(dump.str().find("odometry             = laser"), std::string::npos);

  mrpt::config::CConfigFileMemory bad("[relations_metric]\nodometry = wheels\n");
  try {
    RelationsMetricOptions b;
    b.loadFromConfigFile(bad, "relations_metric");
    FAIL();
  } catch (const gridtopo::InputError& e) {
    EXPECT_EQ(e.field(), "[relations_metric] odometry");
  }
  mrpt::config::CConfigFileMemory neg("[relations_metric]\nmax_time_gap = -1\n");
  RelationsMetricOptions c;
  EXPECT_THROW(c.loadFromConfigFile(neg, "relations_metric"), gridtopo::InputError);
}

TEST(RelationsMetric, EstimateInterpolationVariant) {
  // Straight line at 1 m/s; estimates every 2 s; a relation between t = 1 and t = 5 (both in gaps).
  std::vector<TimedPose> est;
  for (int i = 0; i <= 6; i += 2) est.push_back({double(i), {double(i), 0, 0.0}});
  std::vector<Relation> rel = {{1.0, 5.0, {4.0, 0, 0}, 1}};
  RelationsMetricOptions o;
  // Nearest (ties -> earlier) without odometry: poses of t = 0 and t = 4, error 0 (both 1 m early)...
  const auto plain = evaluateRelations(est, rel, nullptr, o);
  EXPECT_EQ(plain.endpoints_uncorrected, 2u);
  // ...but at t = 1.2 -> 5.2 nearest gives t = 2 and t = 6 ... use an asymmetric relation instead.
  std::vector<Relation> rel2 = {{0.9, 5.2, {4.3, 0, 0}, 1}};
  const auto near = evaluateRelations(est, rel2, nullptr, o);
  EXPECT_NEAR(near.errors[0].translational, std::abs(6.0 - 0.0 - 4.3), 1e-12);
  o.interpolate_estimate = true;
  const auto interp = evaluateRelations(est, rel2, nullptr, o);
  EXPECT_EQ(interp.endpoints_interpolated, 2u);
  EXPECT_NEAR(interp.errors[0].translational, 0.0, 1e-12);
  // With odometry that is exact but in another frame, the blend of both carried poses is exact too.
  std::vector<TimedPose> odo;
  for (int i = 0; i <= 60; ++i) odo.push_back({0.1 * i, TPose2D(5, 5, 1.0) + TPose2D(0.1 * i, 0, 0)});
  const OdometryTrack track(odo);
  const auto both = evaluateRelations(est, rel2, &track, o);
  EXPECT_NEAR(both.errors[0].translational, 0.0, 1e-9);
  // Outside the estimate's time span there is only one side: falls back to the odometry correction.
  std::vector<Relation> rel3 = {{0.0, 5.9, {5.9, 0, 0}, 1}};
  std::vector<TimedPose> short_est(est.begin(), est.begin() + 3);  // up to t = 4
  const auto edge = evaluateRelations(short_est, rel3, &track, o);
  EXPECT_EQ(edge.endpoints_corrected, 1u);
  EXPECT_NEAR(edge.errors[0].translational, 0.0, 1e-9);
}
