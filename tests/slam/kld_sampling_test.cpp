// The adaptive particle set (KLD-sampling, Fox 2003): the bound, the bins, the resampler with a count, and the
// filter on a simulated office loop (libs/sim) with a known trajectory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gridtopo/core/error.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/kld_sampling.h"
#include "gridtopo/slam/rbpf_slam.h"
#include "gridtopo/slam/resampling.h"

using namespace gridtopo;
using namespace gridtopo::slam;

TEST(KldSampling, BoundFollowsFoxEquation13) {
  EXPECT_EQ(kldBound(0, 0.05, 2.326), 1.0);
  EXPECT_EQ(kldBound(1, 0.05, 2.326), 1.0);
  // k = 2, epsilon 0.05, z 2.326: (1 / 0.1) (1 - 2/9 + sqrt(2/9) 2.326)^3 = 65.85
  EXPECT_NEAR(kldBound(2, 0.05, 2.326), 65.85, 0.01);
  // k = 10, epsilon 0.15: (9 / 0.3) (1 - 2/81 + sqrt(2/81) 2.326)^3 = 30 * 1.3408^3 = 72.31
  EXPECT_NEAR(kldBound(10, 0.15, 2.326), 72.31, 0.01);
  // More bins or a tighter bound need more samples; about linear in k for large k.
  for (std::size_t k = 2; k < 200; ++k) EXPECT_LT(kldBound(k, 0.15, 2.326), kldBound(k + 1, 0.15, 2.326));
  EXPECT_GT(kldBound(5, 0.05, 2.326), kldBound(5, 0.15, 2.326));
  EXPECT_NEAR(kldBound(1001, 0.15, 2.326) / kldBound(501, 0.15, 2.326), 1.92, 0.01);
}

TEST(KldSampling, BinsCountDistinctCellsOfPose) {
  const std::vector<Pose2> poses = {{0.01, 0.02, 0.01},  {0.05, 0.08, 0.05}, {0.15, 0.02, 0.01},
                                    {0.01, -0.02, 0.01}, {0.01, 0.02, 0.25}, {0.01, 0.02, 0.01 + 2 * M_PI}};
  EXPECT_EQ(occupiedBins(poses, {0, 1}, 0.1, 0.1), 1u);        // same cell
  EXPECT_EQ(occupiedBins(poses, {0, 2}, 0.1, 0.1), 2u);        // x differs
  EXPECT_EQ(occupiedBins(poses, {0, 3}, 0.1, 0.1), 2u);        // y crosses 0
  EXPECT_EQ(occupiedBins(poses, {0, 4}, 0.1, 0.1), 2u);        // heading differs
  EXPECT_EQ(occupiedBins(poses, {0, 5}, 0.1, 0.1), 1u);        // heading wrapped first
  EXPECT_EQ(occupiedBins(poses, {0, 0, 0, 1}, 0.1, 0.1), 1u);  // copies count once
  EXPECT_EQ(occupiedBins(poses, {0, 1, 2, 4}, 1.0, 1.0), 1u);
}

TEST(KldSampling, CountIsClampedAndFixedWhenNotAdaptive) {
  std::vector<Pose2> tight(30), spread(30);
  for (int i = 0; i < 30; ++i) {
    tight[i] = {0.001 * i, 0.0, 0.0};
    spread[i] = {0.5 * i, 0.0, 0.0};
  }
  std::vector<std::size_t> all(30);
  for (std::size_t i = 0; i < 30; ++i) all[i] = i;
  KldOptions o;
  EXPECT_EQ(kldParticleCount(spread, all, o, 30), 30u);  // min_particles 0: fixed
  EXPECT_EQ(kldParticleCount(tight, all, o, 30), 30u);
  o.min_particles = 5;
  EXPECT_EQ(kldParticleCount(tight, all, o, 30), 5u);    // one bin: the minimum
  EXPECT_EQ(kldParticleCount(spread, all, o, 30), 30u);  // 30 bins: the maximum
  o.epsilon = 0.5;
  const std::vector<std::size_t> three = {0, 10, 20};  // three bins: ceil((2 / 1.0) (1 - 1/9 + sqrt(1/9) z)^3) = 10
  const double c = 1 - 1.0 / 9 + std::sqrt(1.0 / 9) * 2.326;
  EXPECT_EQ(kldParticleCount(spread, three, o, 30), static_cast<std::size_t>(std::ceil(2 / 1.0 * c * c * c)));
  EXPECT_EQ(kldParticleCount(spread, three, o, 30), 10u);
  o.min_particles = 40;  // above the maximum: the maximum
  EXPECT_EQ(kldParticleCount(tight, all, o, 30), 30u);
}

TEST(KldSampling, FailedMatchesCallForTheMaximum) {
  KldOptions o;
  EXPECT_FALSE(growOnFailedMatches(8, 8, 30, o));  // not adaptive
  o.min_particles = 8;
  EXPECT_TRUE(growOnFailedMatches(2, 8, 30, o));   // a quarter of 8
  EXPECT_FALSE(growOnFailedMatches(1, 8, 30, o));
  EXPECT_FALSE(growOnFailedMatches(30, 30, 30, o));  // already at the maximum
  o.grow_failed_fraction = 2.0;
  EXPECT_FALSE(growOnFailedMatches(8, 8, 30, o));  // never
  o.grow_failed_fraction = 0.0;
  EXPECT_TRUE(growOnFailedMatches(0, 8, 30, o));   // always back to the maximum: KLD only shrinks between steps
}

TEST(KldSampling, LowVarianceResampleDrawsAnyCountInProportion) {
  const std::vector<double> w = {0.5, 0.25, 0.125, 0.125};
  Rng a(7, 1, 0, 2), b(7, 1, 0, 2);
  EXPECT_EQ(lowVarianceResample(w, a), lowVarianceResample(w, b, w.size()));  // the old call is count = N
  for (std::size_t count : {1u, 3u, 8u, 16u, 100u}) {
    Rng r(3, count, 0, 2);
    const auto keep = lowVarianceResample(w, r, count);
    ASSERT_EQ(keep.size(), count);
    EXPECT_TRUE(std::is_sorted(keep.begin(), keep.end()));
    for (std::size_t i = 0; i < w.size(); ++i) {
      const double copies = static_cast<double>(std::count(keep.begin(), keep.end(), i));
      EXPECT_LE(std::abs(copies - w[i] * count), 1.0) << "count " << count << " particle " << i;
    }
  }
}

namespace {
struct LoopRun {
  std::vector<TimedPose> trajectory;
  std::vector<int> counts;
  double mean_error = 0;
};
// The simulated office loop (odometry 1.7 m off on average), 30 particles at most, KLD bins of 0.2 m and 0.2 rad.
LoopRun runOfficeLoop(int min_particles, int threads, double eps = 0.5, double bin = 0.2) {
  const auto plan = sim::FloorPlan::officeLoop();
  const auto log = sim::simulate(plan, sim::officeLoopWaypoints(1), sim::SimOptions{});
  SlamOptions o;
  o.particles = 30;
  o.kld.min_particles = min_particles;
  o.kld.epsilon = eps;
  o.kld.bin_xy = bin;
  o.kld.bin_theta = bin;
  o.threads = threads;
  RbpfSlam slam(o);
  for (const auto& r : log.records) slam.processScan(r);
  LoopRun run;
  run.trajectory = slam.trajectory();
  for (const auto& s : slam.stats()) run.counts.push_back(s.particles);
  for (std::size_t i = 0; i < run.trajectory.size(); ++i)
    run.mean_error += std::hypot(run.trajectory[i].pose.x - log.truth[i].x, run.trajectory[i].pose.y - log.truth[i].y);
  run.mean_error /= static_cast<double>(run.trajectory.size());
  return run;
}
}  // namespace

TEST(KldSampling, FilterSpendsFewParticlesWhereTheMatchIsUniqueAndStaysAccurate) {
  const LoopRun fixed = runOfficeLoop(0, 2), adaptive = runOfficeLoop(4, 2);
  ASSERT_EQ(fixed.counts.size(), adaptive.counts.size());
  EXPECT_TRUE(std::all_of(fixed.counts.begin(), fixed.counts.end(), [](int c) { return c == 30; }));
  const auto [lo, hi] = std::minmax_element(adaptive.counts.begin(), adaptive.counts.end());
  double mean = 0;
  for (int c : adaptive.counts) mean += c;
  mean /= static_cast<double>(adaptive.counts.size());
  std::printf("adaptive: particles %d..%d, mean %.1f; error %.4f m (fixed 30: %.4f m)\n", *lo, *hi, mean,
              adaptive.mean_error, fixed.mean_error);
  EXPECT_GE(*lo, 4);
  EXPECT_EQ(adaptive.counts.front(), 30);  // starts at the maximum
  EXPECT_LT(mean, 15.0);                   // half the particles or fewer on the whole (measured 10.2)
  EXPECT_LT(adaptive.mean_error, 0.04);    // and the office loop stays as accurate (measured 0.021 m; fixed 0.030)
  EXPECT_LT(fixed.mean_error, 0.04);
  // Finer bins or a tighter bound ask for more particles.
  const LoopRun finer = runOfficeLoop(4, 2, 0.15, 0.1);
  double finer_mean = 0;
  for (int c : finer.counts) finer_mean += c;
  EXPECT_GT(finer_mean / static_cast<double>(finer.counts.size()), mean + 5.0);
  // The count follows the spread: after it first dropped it rises again somewhere.
  const auto first_drop = std::find_if(adaptive.counts.begin(), adaptive.counts.end(), [](int c) { return c < 30; });
  ASSERT_NE(first_drop, adaptive.counts.end());
  EXPECT_GT(*std::max_element(first_drop, adaptive.counts.end()), *std::min_element(first_drop, adaptive.counts.end()));
}

TEST(KldSampling, AdaptiveSetIsBitIdenticalForAnyNumberOfThreads) {
  const LoopRun one = runOfficeLoop(4, 1), two = runOfficeLoop(4, 2);
  EXPECT_EQ(one.counts, two.counts);
  ASSERT_EQ(one.trajectory.size(), two.trajectory.size());
  for (std::size_t i = 0; i < one.trajectory.size(); ++i) {
    EXPECT_EQ(one.trajectory[i].pose.x, two.trajectory[i].pose.x) << i;
    EXPECT_EQ(one.trajectory[i].pose.phi, two.trajectory[i].pose.phi) << i;
  }
}

TEST(KldSampling, MinimumAboveTheMaximumIsAnInputError) {
  SlamOptions o;
  o.particles = 10;
  o.kld.min_particles = 11;
  EXPECT_THROW(o.validate("test.ini"), InputError);
  o.kld.min_particles = 10;
  EXPECT_NO_THROW(o.validate("test.ini"));
}
